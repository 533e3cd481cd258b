"""tools/bench_matching.py (the matching's scaling benchmark, issue 14), run small in plain CPython."""

import pytest

from tools import bench_matching


def test_the_matching_benchmark_times_right_matchings_and_rejects_bad_sizes(capsys):
    assert bench_matching.main(["--sizes", "20,40", "--markdown"]) == 0
    table = capsys.readouterr().out
    assert "| 20 |" in table and "| 40 |" in table and "x |" in table
    for bad in ("ten", "0", ""):
        with pytest.raises(SystemExit):
            bench_matching.main(["--sizes", bad])
        assert "--sizes" in capsys.readouterr().err
