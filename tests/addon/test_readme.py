"""The README is for animators: its first screen says what the add-on does, shows it, and starts
Install; developer material is linked, not inlined; its promises match the code."""

import os
import re

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
FIRST_SCREEN = 40


def _readme():
    with open(os.path.join(ROOT, "README.md"), encoding="utf-8") as f:
        return f.read()


def _section(text, title):
    match = re.search(rf"(?ms)^## {re.escape(title)}\n(.*?)(?=^## |\Z)", text)
    assert match, f"no section '{title}'"
    return match.group(1)


def test_the_first_screen_says_what_it_does_shows_it_and_starts_install():
    first = _readme().splitlines()[:FIRST_SCREEN]
    assert first[0] == "# Ball-morph In-between"
    assert any("in-betweens for Grease Pencil" in line for line in first[:5])
    assert any(line.startswith("![") and "docs/demo.gif" in line for line in first)
    assert "## Install" in first
    assert not any("make demo" in line or "make test" in line for line in first)


def test_install_uses_blenders_own_tool_with_the_clicks_and_make_build_for_developers():
    install = _section(_readme(), "Install")
    assert "blender --command extension build" in install
    assert "make build" in install
    for click in ("Edit > Preferences > Get Extensions", "Install from Disk..."):
        assert click in install


def test_sections_in_the_animators_order_and_developers_last():
    titles = re.findall(r"(?m)^## (.+)$", _readme())
    assert titles[:2] == ["Install", "Usage"]
    assert titles.index("Limitations") < titles.index("Command line") < titles.index("For developers")
    assert titles[-1] == "For developers"
    developers = _section(_readme(), "For developers")
    assert "make demo" in developers and "make test" in developers
    for page in re.findall(r"\]\((docs/[^)]+)\)", developers):
        assert os.path.exists(os.path.join(ROOT, page)), page


def test_limitations_keep_the_promises_the_code_keeps():
    limits = _section(_readme(), "Limitations")
    assert "Bezier and NURBS strokes come out as POLY" in limits
    # the core's own bounds on resampling (ballmorph_core/geometry/polyline.py)
    with open(os.path.join(ROOT, "ballmorph_core", "geometry", "polyline.py"), encoding="utf-8") as f:
        source = f.read()
    low = int(re.search(r"^DEFAULT_SAMPLES_MIN = (\d+)", source, re.M).group(1))
    high = int(re.search(r"^DEFAULT_SAMPLES_MAX = (\d+)", source, re.M).group(1))
    assert f"from about {low} to about {high:,} samples" in limits
    assert "1.25" not in _readme()  # the old promise (at most 1.25 times the denser key) was not kept
