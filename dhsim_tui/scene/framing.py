"""Where each view looks and how close: the framings the simulator's views
and ``dhsim draw`` share.

* **The work area** (``0``, or ``F`` from fitted): the three orthographic views share one
  scale, the smallest that shows the seed's work area in each (100 mm is as
  many columns in every view), each centred on its part of it; the 3-D view
  shows the floor and the arm (``oblique.picture_bounds``).
* **Fitted** (the simulator's views as they open, ``F``, ``dhsim draw
  --fit``): each view on the arm as it stands, links, joints, tool and the
  frame axes drawn, and the program's path while one is drawn, with a
  small margin.

A framing is a centre in the view's plane and the length one braille dot
stands for; ``zoomed`` narrows it. No UI here: the views panel keeps the
state (what is fitted, what the zoom is) and asks these for the numbers.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from dhsim_tui.scene.projection import ViewScene, fit_framing_bounds, limits_at, per_dot_needed


@dataclass(frozen=True)
class Framing:
    """Where a view looks and how close: its centre (in the view's plane)
    and the length one braille dot stands for (robot units)."""

    centre: tuple[float, float]
    per_dot: float

    def zoomed(self, zoom: float, centre: tuple[float, float] | None = None) -> Framing:
        """Closer by ``zoom`` (about ``centre`` if given)."""
        return Framing(centre if centre is not None else self.centre, self.per_dot / zoom)


def _middle(bounds: tuple[float, float, float, float]) -> tuple[float, float]:
    return ((bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2)


def framing_of(bounds: tuple[float, float, float, float], cols: int, rows: int) -> Framing:
    """The closest framing of ``cols`` × ``rows`` braille cells that shows ``bounds``."""
    return Framing(_middle(bounds), per_dot_needed(bounds, cols, rows))


def work_area_framings(
    scenes: Sequence[ViewScene], canvases: Sequence[tuple[int, int]]
) -> list[Framing]:
    """The default framings: one scale for the orthographic views (each
    centred on its bounds), the 3-D view on its own bounds."""
    flat = [i for i, scene in enumerate(scenes) if not scene.view.is_3d]
    ortho = max(
        (per_dot_needed(scenes[i].bounds, *canvases[i]) for i in flat),
        default=1.0,
    )
    return [
        framing_of(scene.bounds, *canvas)
        if scene.view.is_3d
        else Framing(_middle(scene.bounds), ortho)
        for scene, canvas in zip(scenes, canvases, strict=True)
    ]


def fit_bounds(scene: ViewScene) -> tuple[float, float, float, float]:
    """What ``F`` keeps in the picture: the links, joints, tool, the axes
    drawn and the program's path drawn."""
    return scene.fit_bounds or scene.arm_bounds or scene.bounds


#: F keeps the links at least this share of the picture's height or width
LINKS_SHARE = 0.62


def links_share(
    links: tuple[float, float, float, float], framing: Framing, cols: int, rows: int
) -> float:
    """How much of the picture's width or height (the larger) the links span."""
    (x0, x1), (y0, y1) = limits_at(framing.centre, framing.per_dot, cols, rows)
    return max((links[1] - links[0]) / (x1 - x0), (links[3] - links[2]) / (y1 - y0))


def _union(
    a: tuple[float, float, float, float] | None, b: tuple[float, float, float, float] | None
) -> tuple[float, float, float, float] | None:
    if a is None or b is None:
        return a or b
    return (min(a[0], b[0]), max(a[1], b[1]), min(a[2], b[2]), max(a[3], b[3]))


def fitted(scene: ViewScene, cols: int, rows: int, least: float) -> Framing:
    """The view on the arm as it stands: its links, joints, tool and the
    frame axes drawn, with a small margin; never narrower than ``least``
    across (an arm seen end-on is a point).

    Axes that would leave the links less than ``LINKS_SHARE`` of the
    picture (long axes of frames sharing an origin, an arm seen nearly
    end-on) are let run off its edge: the picture is fitted to the links
    (and the program's path, when one is drawn)."""
    framing = framing_of(fit_framing_bounds(fit_bounds(scene), least), cols, rows)
    links = _union(scene.arm_bounds, scene.path_bounds)
    if links is None or links_share(links, framing, cols, rows) >= LINKS_SHARE:
        return framing
    return framing_of(fit_framing_bounds(links, least), cols, rows)
