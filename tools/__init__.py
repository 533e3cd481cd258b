"""The dev tools (demo, benchmarks, scenes report, real-data benchmark): scripts run as
``python tools/<name>.py``, and a package only so that their own tests (tests/tools/) import them
as ``from tools import realdata`` without changing ``sys.path``. The core's tests never import
this package; the drawings tests and tools share live in tests/fixtures/.
"""
