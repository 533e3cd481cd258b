# Two commands matter: `make demo` (the main job) and `make test` (everything CI runs).
# Both bootstrap their own cached Python 3.11 + bpy environments (tools/bootstrap.sh).

.PHONY: demo test lint build core-demo evaluate

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
