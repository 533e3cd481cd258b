# Two commands matter: `make demo` (the main job) and `make test` (everything CI runs).
# Both bootstrap their own cached Python 3.11 + bpy environments (tools/bootstrap.sh).

.PHONY: demo test lint build core-demo evaluate bench fuzz scenes realdata realdata-heldout

demo:
	tools/demo.sh

test:
	tools/run_tests.sh

lint:
	$$(dirname $$(tools/bootstrap.sh 5.0.1))/ruff check . && $$(dirname $$(tools/bootstrap.sh 5.0.1))/ruff format --check .

build:
	tools/build_extension.sh

core-demo:
	$$(tools/bootstrap.sh 5.0.1) tools/core_demo.py

evaluate:
	$$(tools/bootstrap.sh 5.0.1) tools/evaluate.py

# The animator-style scenes of issues 11 and 12 (tests/fixtures/scenes/): every figure of the core next to
# the Blender-like baseline, in a few seconds (tools/scenes_blender.py adds Blender's own Interpolate).
scenes:
	$$(tools/bootstrap.sh 5.0.1) tools/scenes_report.py

# The benchmark tools: tools/benchmark.py (inside bpy) runs tools/bench_ballmap.py and bench_matching.py (plain CPython)
# itself and writes docs/benchmark.md; 10-12 minutes on two shared cores.
bench:
	timeout 3600 $$(tools/bootstrap.sh 5.0.1) tools/benchmark.py --write docs/benchmark.md

# The long fuzz target (issue 7): thousands of random curve pairs and drawings per test
# (HYPOTHESIS_PROFILE=fuzz, FUZZ_EXAMPLES to change the count); `make test` runs its short
# profile. The address space is capped so a memory blow-up fails as a MemoryError instead of
# exhausting the machine; pytest-timeout's per-test limit is lifted (3,000 examples per test:
# about 5 minutes in all on two cores). RuntimeWarnings are errors (tests/fuzz/conftest.py marks
# every fuzz test so; -W says it here too).
fuzz:
	py=$$(tools/bootstrap.sh 5.0.1) && ulimit -v 8000000 && \
	HYPOTHESIS_PROFILE=fuzz timeout 14400 $$py -m pytest -q -W error::RuntimeWarning --timeout=0 tests/fuzz --hypothesis-show-statistics

# The real-data benchmark (issues 11, 38): glyph outlines of Inter (variable: Thin and Black
# masters as keys, instances at weights 300-700 as ground truth) and of four families of static
# instances of one design (Dosis, League Spartan, JetBrains Mono, Manrope: lightest and heaviest
# as keys, the others as ground truth); writes docs/realdata.md and docs/realdata.png (a few
# minutes on two cores). It needs the Debian packages below, installed here when running as root
# with apt-get; otherwise the tool stops and says how (INTER_FONT_DIR=... points it at the
# Inter fonts elsewhere).
INTER_FONT_DIR ?= /usr/share/fonts/truetype/inter-vf
INTER_FONTS = Inter-roman.var.ttf Inter-italic.var.ttf InterDisplay-roman.var.ttf
REALDATA_PACKAGES = fonts-dosis fonts-league-spartan fonts-jetbrains-mono fonts-manrope
realdata:
	@for f in $(INTER_FONTS); do [ -f "$(INTER_FONT_DIR)/$$f" ] || missing="fonts-inter-variable"; done; \
	for p in $(REALDATA_PACKAGES); do dpkg -s $$p >/dev/null 2>&1 || missing="$$missing $$p"; done; \
	if [ -n "$$missing" ] && [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null; then \
		echo "realdata: installing$$missing (the benchmark's fonts)"; \
		DEBIAN_FRONTEND=noninteractive apt-get install -y $$missing || \
		{ apt-get update && DEBIAN_FRONTEND=noninteractive apt-get install -y $$missing; }; \
	fi
	INTER_FONT_DIR="$(INTER_FONT_DIR)" $$(tools/bootstrap.sh 5.0.1) tools/realdata.py --write docs/realdata.md

# The same benchmark on families held back (tools/realdata.py HELD_OUT_FAMILIES: other designers,
# never used to choose a rule or a constant); writes docs/realdata-heldout.md.
HELDOUT_PACKAGES = fonts-firacode fonts-lato fonts-open-sans fonts-quicksand fonts-roboto-unhinted fonts-yrsa-rasa fonts-karla fonts-cantarell
realdata-heldout:
	@for p in $(HELDOUT_PACKAGES); do dpkg -s $$p >/dev/null 2>&1 || missing="$$missing $$p"; done; \
	if [ -n "$$missing" ] && [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null; then \
		echo "realdata: installing$$missing (the held-out fonts)"; \
		DEBIAN_FRONTEND=noninteractive apt-get install -y $$missing || \
		{ apt-get update && DEBIAN_FRONTEND=noninteractive apt-get install -y $$missing; }; \
	fi
	$$(tools/bootstrap.sh 5.0.1) tools/realdata.py --held-out --write docs/realdata-heldout.md
