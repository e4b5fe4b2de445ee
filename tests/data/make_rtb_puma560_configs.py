"""Make rtb_puma560_configs.json: Puma 560 joint vectors and the configuration
letters the Robotics Toolbox for Python gives them (l/r shoulder, u/d elbow,
n/f wrist), the reference for tests/core/test_ik_labels_rtb.py.

Runs only where the toolbox is installed, never in the project's environment
(it is not a dependency of dhsim). In a scratch virtual environment::

    python3 -m venv /tmp/rtbenv
    /tmp/rtbenv/bin/pip install "roboticstoolbox-python==1.5.*"
    /tmp/rtbenv/bin/python tests/data/make_rtb_puma560_configs.py

How a vector gets its letters: the pose ``fkine(q)`` is solved by
``Puma560.ikine_a`` in each of its 8 configurations ("lun", "luf", ...), and
the one configuration whose solution equals ``q`` (every joint within
``SAME`` degrees, modulo 360) names it. Vectors are drawn uniformly within
the joint limits (seeded); a vector is skipped when joint 5 is within
``WRIST_MARGIN`` degrees of the wrist's singular position (0 or 180: there
"n" and "f" are one solution) or when not exactly one configuration
reproduces it (at a shoulder or elbow singularity). Angles are stored in
degrees, rounded to ``DECIMALS``, and the letters are found for the rounded
values. The three vectors quoted in issue 17 come first.
"""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

import numpy as np
import roboticstoolbox as rtb

SEED = 17
COUNT = 300  # random vectors kept, besides the quoted ones
DECIMALS = 3
SAME = 1e-6  # degrees
WRIST_MARGIN = 2.0  # degrees
CONFIGS = tuple(s + e + w for s in "lr" for e in "ud" for w in "nf")
QUOTED = (
    ([0.0, 30.0, 45.0, 100.0, 40.0, 20.0], "luf"),  # issue 17
    ([0.0, 30.0, 45.0, -80.0, -40.0, -160.0], "lun"),  # issue 17
    ([10.0, 40.0, -100.0, 20.0, 30.0, 40.0], "ruf"),  # dhsim's README example
)
OUT = Path(__file__).with_name("rtb_puma560_configs.json")


def configs_of(puma, q_deg) -> list[str]:
    """Every ikine_a configuration whose solution for fkine(q) is q."""
    q = np.radians(q_deg)
    pose = puma.fkine(q)
    found = []
    for config in CONFIGS:
        sol = puma.ikine_a(pose, config)
        if not sol.success:
            continue
        gap = np.degrees(np.remainder(np.asarray(sol.q) - q + math.pi, 2 * math.pi) - math.pi)
        if np.max(np.abs(gap)) < SAME:
            found.append(config)
    return found


def main() -> int:
    puma = rtb.models.DH.Puma560()
    pairs = []
    for q, config in QUOTED:
        found = configs_of(puma, q)
        if found != [config]:
            print(f"{q}: the toolbox says {found}, the issue quotes {config!r}", file=sys.stderr)
            return 1
        pairs.append({"q": q, "config": config})
    low, high = np.degrees(puma.qlim)
    rng = np.random.default_rng(SEED)
    skipped = 0
    while len(pairs) < COUNT + len(QUOTED):
        q = [round(float(v), DECIMALS) for v in rng.uniform(low, high)]
        if abs(math.sin(math.radians(q[4]))) < math.sin(math.radians(WRIST_MARGIN)):
            skipped += 1
            continue
        found = configs_of(puma, q)
        if len(found) != 1:
            skipped += 1
            continue
        pairs.append({"q": q, "config": found[0]})
    OUT.write_text("[\n" + ",\n".join(json.dumps(p) for p in pairs) + "\n]\n")  # a pair a line
    counts = {c: sum(p["config"] == c for p in pairs) for c in CONFIGS}
    print(f"{OUT.name}: {len(pairs)} pairs ({skipped} vectors skipped), {counts}")
    print(f"roboticstoolbox-python {rtb.__version__}, numpy {np.__version__}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
