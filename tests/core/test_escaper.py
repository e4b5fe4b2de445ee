"""One escaper for every text dhsim shows (``model.text.printable``).

The fault campaign found invisible and bidirectional characters reaching
the terminal raw from names, pose names and keys: U+061C (the Arabic letter
mark, a bidi control), tag characters such as U+E0041 and U+FFF9 (an
interlinear annotation anchor). Every character of the categories Cc, Cf,
Co, Cs, Zl and Zp and every bidi control is now written as a visible escape
wherever text is shown, by the same function the URDF export uses. Names
refuse the part of that set that steers a terminal or the direction of text
or hides inside a name (controls, surrogates, separators, bidi controls,
zero-width characters): U+061C joins the refused bidi controls; the other
format and private-use characters stay allowed in names, shown escaped.
Ordinary text of any script passes unchanged.
"""

from __future__ import annotations

import codecs
import json
import unicodedata

import pytest

from dhsim_tui.cli.main import main
from dhsim_tui.core.interop.export import export_text
from dhsim_tui.core.model.errors import DhsimError
from dhsim_tui.core.model.robot import Joint, Robot
from dhsim_tui.core.model.text import control_character, escaped, is_control, printable

#: written out here, independently of dhsim_tui.core.model.text
CATEGORIES = {"Cc", "Cf", "Co", "Cs", "Zl", "Zp"}
BIDI = "\u061c\u200e\u200f\u202a\u202b\u202c\u202d\u202e\u2066\u2067\u2068\u2069"
#: what a name may not hold: controls, surrogates, separators, bidi controls,
#: zero-width space / non-joiner / joiner, word joiner, byte order mark
REFUSED_CATEGORIES = {"Cc", "Cs", "Zl", "Zp"}
ZERO_WIDTH = "\u200b\u200c\u200d\u2060\ufeff"
#: the campaign's characters
CAMPAIGN = {"\u061c": "\\u061c", "\U000e0041": "\\U000e0041", "\ufff9": "\\ufff9"}
ARM = "[[joints]]\ntheta = 0\nd = 0\na = 100\nalpha = 0\n"


def arm(name: str = "arm", poses=()) -> Robot:
    return Robot(name=name, joints=(Joint(a=100.0),), poses=poses)


def toml_string(text: str) -> str:
    """``text`` as a TOML basic string (JSON's escapes of quotes, backslashes
    and controls are TOML's; other characters are written as they are)."""
    return json.dumps(text, ensure_ascii=False)


@pytest.mark.parametrize("char", CAMPAIGN, ids=[c[1:] for c in CAMPAIGN.values()])
def test_the_campaigns_characters_are_shown_escaped(char):
    assert printable(f"arm{char}x") == f"arm{CAMPAIGN[char]}x"


def test_every_character_of_the_categories_and_every_bidi_control_is_escaped_and_no_other():
    wrong = []
    for code in range(0x110000):
        char = chr(code)
        expected = unicodedata.category(char) in CATEGORIES or char in BIDI
        shown = printable(char)
        if (shown != char) != expected or is_control(char) != expected:
            wrong.append(hex(code))
        elif expected:  # a visible escape that reads back as the character
            assert shown.isascii() and shown.isprintable(), hex(code)
            assert shown == escaped(char)
            if unicodedata.category(char) != "Cs":
                assert codecs.decode(shown, "unicode_escape") == char, hex(code)
    assert not wrong, wrong[:20]


def test_a_name_refuses_what_steers_and_every_refused_character_is_also_escaped():
    wrong = []
    for code in range(0x110000):
        char = chr(code)
        refused = (
            unicodedata.category(char) in REFUSED_CATEGORIES or char in BIDI or char in ZERO_WIDTH
        )
        if (control_character(f"a{char}b") is not None) != refused:
            wrong.append(hex(code))
        if refused and not is_control(char):
            wrong.append(f"refused but not escaped: {code:#x}")
    assert not wrong, wrong[:20]


@pytest.mark.parametrize(
    "text",
    [
        "Braço",
        "机器人 🤖",
        "ロボットアーム",
        "Roboter ä ö ü ß",
        "ذراع آلية ١٢٣",  # Arabic letters and digits: no control among them
        "זרוע רובוטית",
        "e\u0301 a\u0308",  # combining marks
        "⚠\ufe0f #\ufe0f\u20e3",  # variation selector, enclosing keycap
        "a\u00a0b\u3000c",  # no-break and ideographic spaces
        "back\\slash \\x1b as typed",
    ],
)
def test_ordinary_text_of_any_script_passes_unchanged(text):
    assert printable(text) == text
    assert control_character(text) is None
    assert arm(text).name == text  # and is a valid name


def test_the_zero_width_joiner_is_shown_escaped_and_refused_in_a_name():
    family = "👨\u200d👩\u200d👧"
    assert printable(family) == "👨\\u200d👩\\u200d👧"
    with pytest.raises(DhsimError, match=r"may not hold control characters \(\\u200d\)"):
        arm(family)


def test_the_arabic_letter_mark_is_refused_in_names_like_every_bidi_control():
    with pytest.raises(DhsimError) as caught:
        arm("arm\u061c42")
    assert str(caught.value) == "name: a robot name may not hold control characters (\\u061c)"
    with pytest.raises(DhsimError, match=r'poses\."up\\u061cdown": a pose name may not hold'):
        arm(poses=(("up\u061cdown", (0.0,)),))


def test_names_with_other_invisible_characters_stay_valid_and_are_shown_escaped(capsys, tmp_path):
    name = "arm\U000e0041\ufff9x\u00ad\ue000"
    shown = "arm\\U000e0041\\ufff9x\\xad\\ue000"
    pose = "ready\U000e0041"
    path = tmp_path / "arm.toml"
    path.write_text(
        f"name = {toml_string(name)}\n[poses]\n{toml_string(pose)} = [5]\n" + ARM,
        encoding="utf-8",
    )
    outputs = []
    for argv in (
        ["check", str(path)],
        ["fk", str(path), "--pose", pose],
        ["ik", str(path), "--xyz", "1e6,0,0"],  # no solution: the name in the error
        ["fk", str(path), "--pose", "gone\ufff9"],  # no such pose: the poses listed
    ):
        main(argv)
        out, err = capsys.readouterr()
        outputs.append(out + err)
    text = "".join(outputs)
    assert shown in outputs[0] and shown in outputs[1] and shown in outputs[2]
    assert "ready\\U000e0041" in outputs[3] and "gone\\ufff9" in outputs[3]
    raw = sorted({hex(ord(c)) for c in text if is_control(c) and c != "\n"})
    assert not raw, raw


def test_an_unknown_key_from_a_file_is_shown_escaped(capsys, tmp_path):
    path = tmp_path / "arm.toml"
    key = toml_string("k\u061c\ufff9")
    path.write_text(f'name = "arm"\n{key} = 1\n' + ARM, encoding="utf-8")
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err
    assert "k\\u061c\\ufff9: unknown key" in err
    assert not any(is_control(c) for c in err.strip())


def test_the_urdf_export_shows_the_name_through_the_same_escaper():
    # the robot's name in the header comment and in <robot name="...">; the
    # stored robot (dhsim's JSON comment, read back on import) keeps it exact
    urdf = export_text(arm("arm\U000e0041\ufff9\ufffex"), "urdf")
    shown = "arm\\U000e0041\\ufff9\\ufffex"  # U+FFFE: a character XML cannot hold
    lines = urdf.splitlines()
    header = next(line for line in lines if "Exported by dhsim from robot" in line)
    robot = next(line for line in lines if line.startswith("<robot name="))
    assert json.dumps(shown) in header  # quoted as a JSON string there
    assert robot == f'<robot name="{shown}">'
    for line in (header, robot):
        assert not any(is_control(c) or c == "\ufffe" for c in line), ascii(line)
