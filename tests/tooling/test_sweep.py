"""gpl2py.sweep without a cluster: parameter files, the rows of runs that end in every way, the
metrics, the table written as the rows arrive and resumed, the plot.  (The Dask engine, a killed
worker and the engines' agreement: test_sweep_cluster.py.)"""

from __future__ import annotations

import math
from pathlib import Path

import pandas as pd
import pytest

from gpltest import SAMPLES
from sweepkit import NO_MODULE_LINE, RAISE_LINE, THROW_LINE, tiny_project

from gpl2py.sweep import Count, EndTime, EventTime, ParamsError, Sweep, draws, grid, read_params, run_id
from gpl2py.sweep.metrics import from_table
from gpl2py.sweep.results import parts_folder

# -- parameter sets ------------------------------------------------------------------------------


def test_a_grid_is_every_combination_with_the_first_name_slowest() -> None:
    assert grid(interval=[0.2, 1.0], speed=[20, 80], robot="PF400SX") == [
        {"interval": 0.2, "speed": 20, "robot": "PF400SX"}, {"interval": 0.2, "speed": 80, "robot": "PF400SX"},
        {"interval": 1.0, "speed": 20, "robot": "PF400SX"}, {"interval": 1.0, "speed": 80, "robot": "PF400SX"}]


def test_random_draws_are_the_same_for_the_same_seed_and_stay_in_their_ranges() -> None:
    spec = {"interval": {"uniform": [0.1, 2.0]}, "seed": {"integers": [0, 9]}, "speed": {"choice": [20, 50]}}
    first, again, other = draws(50, 7, **spec), draws(50, 7, **spec), draws(50, 8, **spec)
    assert first == again and first != other
    assert all(0.1 <= p["interval"] <= 2.0 and p["seed"] in range(10) and p["speed"] in (20, 50) for p in first)


def test_toml_files_give_a_grid_a_list_or_draws_with_metrics_and_a_plot(tmp_path: Path) -> None:
    path = tmp_path / "p.toml"
    path.write_text('[grid]\ninterval = [0.2, 0.5]\nspeed = 50\n[metrics]\nparts = { count = "^placed" }\n'
                    'grips = { count = 1 }\ndone = { time = "^cell done" }\n[plot]\nmetric = "parts"\nx = "interval"\n')
    found = read_params(path)
    assert found.sets == [{"interval": 0.2, "speed": 50}, {"interval": 0.5, "speed": 50}]
    assert found.plot == {"metric": "parts", "x": "interval"}
    metrics = from_table(found.metrics)
    assert metrics[3:] == [Count("parts", "^placed"), Count("grips", signal=1), EventTime("done", "^cell done")]
    path.write_text('[[run]]\nspeed = 20\n[[run]]\nspeed = 80\n[[run]]\nspeed = 20\n')
    assert read_params(path).sets == [{"speed": 20}, {"speed": 80}]  # a set given twice runs once
    path.write_text('[random]\ncount = 3\nseed = 1\n[random.params]\nspeed = { integers = [1, 100] }\n'
                    'seed = { integers = [0, 9] }\n')
    assert read_params(path).sets == draws(3, 1, speed={"integers": [1, 100]}, seed={"integers": [0, 9]})


def test_csv_files_read_numbers_and_booleans(tmp_path: Path) -> None:
    path = tmp_path / "p.csv"
    path.write_text("interval,speed,robot,fast\n0.2,20,PF400SX,true\n1.5,80,PF3400,false\n")
    assert read_params(path).sets == [{"interval": 0.2, "speed": 20, "robot": "PF400SX", "fast": True},
                                      {"interval": 1.5, "speed": 80, "robot": "PF3400", "fast": False}]


@pytest.mark.parametrize(("name", "text", "says"), [
    ("p.toml", "[grid]\na = [1]\n[[run]]\nb = 2\n", "exactly one of [grid], [[run]] or [random] (found: grid, run)"),
    ("p.toml", "[random]\ncount = 2\nseed = 1\n[random.params]\na = { normal = [0, 1] }\n", "unknown draw 'normal'"),
    ("p.toml", "[random]\ncount = 2\nseed = 1\na = { uniform = [0, 1] }\n", "[random] holds count, seed and"),
    ("p.toml", "[grid]\na = []\n", "a has no values"),
    ("p.toml", "[grid\n", "p.toml: Expected ']'"),
    ("p.csv", "a,b\n1,2\n3\n", "p.csv:3: 1 values for 2 names"),
    ("p.json", "{}", "a parameter file is .toml or .csv"),
])
def test_a_wrong_parameter_file_says_where(tmp_path: Path, name: str, text: str, says: str) -> None:
    path = tmp_path / name
    path.write_text(text)
    with pytest.raises(ParamsError, match=None) as info:
        read_params(path)
    assert says in str(info.value)


def test_a_run_id_names_the_values_not_their_order() -> None:
    assert run_id({"a": 1, "b": 0.5}) == run_id({"b": 0.5, "a": 1}) != run_id({"a": 1, "b": 0.25})


# -- the rows ----------------------------------------------------------------------------------------


@pytest.fixture
def tiny(tmp_path: Path) -> tuple[str, Path]:
    return tiny_project(tmp_path)


def _sweep(tiny: tuple[str, Path], sets: list[dict[str, object]], **options: object) -> Sweep:
    project, setup = tiny
    metrics = [EndTime(), Count("made", "^part "), Count("grips", signal=1), EventTime("done_at", "^done")]
    return Sweep(project, setup, sets, metrics=metrics, **options)  # type: ignore[arg-type]


def test_every_way_a_run_ends_is_a_row_and_the_others_go_on(tiny: tuple[str, Path]) -> None:
    sets = [{"mode": m, "parts": 2} for m in ("ok", "fail", "stall", "loop", "setup")]
    df = _sweep(tiny, sets, timeout=5.0).run_in_process().set_index("mode")
    assert list(df["status"]) == ["ok", "error", "stalled", "timeout", "setup error"]
    ok, fail, stall, loop, setup = (df.loc[m] for m in ("ok", "fail", "stall", "loop", "setup"))
    assert (ok["made"], ok["grips"], ok["done_at"], ok["end_time"]) == (2, 2, 0.5, 0.5)
    assert (fail["error_code"], fail["error_file"], fail["error_line"], fail["error_thread"]) == \
        (-3100, "Main.gpl", THROW_LINE, "Main")
    assert fail["made"] == 0 and math.isnan(fail["done_at"])
    assert stall["stalled_threads"] == "Main" and pd.isna(stall["error_code"])
    assert loop["end_time"] == 5.0 and "time-out, 5 s of controller time" in loop["error_message"]
    assert (setup["error_file"], setup["error_line"]) == ("tiny_setup.py", RAISE_LINE)
    assert setup["error_message"] == "setup raised ValueError: no conveyor on this cell"


def test_a_setup_error_raised_inside_gpl2py_names_the_setup_files_line(tiny: tuple[str, Path]) -> None:
    [row] = _sweep(tiny, [{"mode": "nomodule", "parts": 1}]).run_in_process().to_dict("records")
    assert row["status"] == "setup error"
    assert (row["error_file"], row["error_line"]) == ("tiny_setup.py", NO_MODULE_LINE)  # not notebook.py's
    assert "no module 'Conveyor' in this project" in row["error_message"]


def test_a_fault_of_the_runtime_is_a_crashed_row_naming_where_and_the_others_go_on(
        tiny: tuple[str, Path], monkeypatch: pytest.MonkeyPatch) -> None:
    from gplrt.sim import Simulation

    real = Simulation.install_project_files
    calls: list[str] = []

    def broken(sim: Simulation, files: object, project: str) -> None:
        calls.append(project)
        if len(calls) == 2:  # the second run only
            raise RuntimeError("flash disk gone")
        real(sim, files, project)

    monkeypatch.setattr(Simulation, "install_project_files", broken)
    df = _sweep(tiny, [{"mode": "ok", "parts": n} for n in (1, 2, 3)]).run_in_process()
    assert list(df["status"]) == ["ok", "crashed", "ok"] and list(df["made"]) == [1, 0, 3]
    crashed = df.iloc[1]
    line = next(i for i, text in enumerate(Path(__file__).read_text().splitlines(), 1) if '"flash disk gone"' in text)
    assert crashed["error_message"] == f"RuntimeError: flash disk gone (at {Path(__file__).name}:{line})"
    assert crashed["error_thread"] is None  # a thread's name, never a traceback


def test_the_rows_hold_the_parameters_as_columns_in_the_sets_order(tiny: tuple[str, Path]) -> None:
    df = _sweep(tiny, [{"mode": "ok", "parts": n} for n in (3, 1, 2)]).run_in_process()
    assert list(df.columns[:3]) == ["mode", "parts", "status"]
    assert list(df["parts"]) == list(df["made"]) == [3, 1, 2]
    assert list(df["end_time"]) == [0.75, 0.25, 0.5]
    assert list(df["run_id"]) == [run_id({"mode": "ok", "parts": n}) for n in (3, 1, 2)]


def test_a_parameter_named_as_a_column_of_the_metrics_is_refused(tiny: tuple[str, Path]) -> None:
    for name in ("made", "done_at", "status", "end_time", "run_id"):
        with pytest.raises(ParamsError, match=f"parameter {name!r} has the name of a column"):
            _sweep(tiny, [{"mode": "ok", name: 1}])
    with pytest.raises(ParamsError, match="parameter 'peak_speed_Z' has the name of a column"):
        Sweep(tiny[0], tiny[1], [{"peak_speed_Z": 1}])  # the default metrics
    with pytest.raises(ParamsError, match="robot 'PF9' is not a robot model; one of ARM6, "):
        _sweep(tiny, [{"mode": "ok", "robot": "PF9"}])


def test_a_project_with_errors_is_refused_before_any_run(tmp_path: Path) -> None:
    from gpltest import write_project

    from gpl2py.sweep import SweepError

    project = write_project(tmp_path, {"Main.gpl": "Module Main\n    Public Sub Main()\n        x = \n"
                                                   "    End Sub\nEnd Module\n"})
    with pytest.raises(SweepError, match="could not be translated"):
        Sweep(project, None, [{"a": 1}])


VPLUS_CELL = """\
.PROGRAM main()
  n = 2
  IF SIG(1001) THEN
    n = 4
  END
  FOR i = 1 TO n
    TYPE "part ", i
    WAIT.EVENT , 0.5
  END
  TYPE "done"
.END
"""


def _more_parts(sim: object, params: dict[str, object]) -> None:
    sim.io.set_input(10001, params["many"])  # type: ignore[attr-defined]  # V+ input 1001 (gplrt.vplus.signals)


def test_a_v_plus_project_is_swept_as_a_gpl_one(tmp_path: Path) -> None:
    source = tmp_path / "cell.v2"
    source.write_text(VPLUS_CELL)
    sweep = Sweep(source, _more_parts, [{"many": False}, {"many": True}],
                  metrics=[EndTime(), Count("parts", "^part "), EventTime("done_at", "^done")])
    df = sweep.run_in_process()
    assert list(df["status"]) == ["ok", "ok"]
    assert list(df["parts"]) == [2, 4] and list(df["done_at"]) == [1.0, 2.0]


def test_a_tmscript_project_is_refused_before_any_run(tmp_path: Path) -> None:
    from gpl2py.sweep import SweepError

    source = tmp_path / "cell.tms"
    source.write_text('main\n{\n    Display("Green", "Yellow", "Result", "part")\n}\n')
    with pytest.raises(SweepError, match="a TMscript project cannot be swept yet"):
        Sweep(source, None, [{"a": 1}])


def test_the_sample_measures_motion_and_its_conveyor_and_speed_change_the_cycle() -> None:
    sweep = Sweep.from_file(SAMPLES / "pick_and_place", SAMPLES / "sweep" / "params.toml",
                            SAMPLES / "sweep" / "setup.py")
    sweep.sets = [{"interval": i, "speed": s} for i, s in ((0.2, 20), (0.2, 80), (1.0, 80), (6.0, 80))]
    df = sweep.run_in_process().set_index(["interval", "speed"])
    assert list(df["parts"]) == [8, 8, 8, 0] and list(df["stopped"]) == [0, 0, 0, 1]
    slow, fast, late, starved = (df.loc[k] for k in ((0.2, 20), (0.2, 80), (1.0, 80), (6.0, 80)))
    assert slow["done_at"] > fast["done_at"]  # a slower Profile: a longer cycle
    assert late["done_at"] == pytest.approx(fast["done_at"] + 8 * 0.8, abs=0.01)  # 0.8 s more per part
    assert math.isnan(starved["done_at"])  # the Feeder gave up after 5 s: the cell stopped
    assert fast["motion_time"] < slow["motion_time"] < slow["end_time"]
    # Speed 20 and 80 of the same Profile: the wrist's peak speed scales with it (72 and 288 deg/s).
    assert (slow["peak_speed_Wrist"], fast["peak_speed_Wrist"]) == (72.0, 288.0)


def test_a_parameter_named_robot_is_the_robot_model_of_its_run() -> None:
    sweep = Sweep.from_file(SAMPLES / "pick_and_place", SAMPLES / "sweep" / "params.toml",
                            SAMPLES / "sweep" / "setup.py", timeout=5.0)
    sweep.sets = [{"interval": 0.2, "speed": 80, "robot": r} for r in ("PF400SX", "ARM6", "PF400SXL")]
    df = sweep.run_in_process().set_index("robot")
    # Each model's own joints (a SCARA's Z, the six-axis arm's Base and Wrist1, the PF400SXL's
    # Rail) and its own limits (the PF400SXL's Z is faster at the same Speed).
    assert math.isnan(df.loc["ARM6", "peak_speed_Z"]) and math.isnan(df.loc["PF400SX", "peak_speed_Base"])
    assert df.loc["ARM6", "peak_speed_Base"] > 0 and df.loc["ARM6", "peak_speed_Wrist1"] > 0
    assert math.isnan(df.loc["PF400SX", "peak_speed_Rail"]) and df.loc["PF400SXL", "peak_speed_Rail"] == 0.0
    assert df.loc["PF400SXL", "peak_speed_Z"] > df.loc["PF400SX", "peak_speed_Z"]


# -- the table, written as the rows arrive -----------------------------------------------------------


def test_rows_written_before_an_interruption_are_kept_and_resume_runs_only_the_rest(
        tiny: tuple[str, Path], tmp_path: Path) -> None:
    out = tmp_path / "results.parquet"
    sweep = _sweep(tiny, [{"mode": "ok", "parts": n} for n in range(1, 7)])

    def interrupt_after_three(done: int, total: int) -> None:
        if done == 3:
            raise KeyboardInterrupt  # Ctrl-C in the middle of the sweep

    with pytest.raises(KeyboardInterrupt):
        sweep.run_in_process(output=out, progress=interrupt_after_three)
    assert not out.exists()
    kept = pd.concat(pd.read_parquet(p) for p in sorted(parts_folder(out).glob("part-*.parquet")))
    assert sorted(kept["parts"]) == [1, 2, 3]
    assert sweep.already_done(out) == 3

    seen: list[int] = []
    df = sweep.run_in_process(output=out, resume=True, progress=lambda done, total: seen.append(total))
    assert seen == [3, 3, 3]  # only the three sets not yet in the output ran
    assert list(df["parts"]) == [1, 2, 3, 4, 5, 6] and df["run_id"].is_unique
    pd.testing.assert_frame_equal(pd.read_parquet(out), df)
    assert not parts_folder(out).exists()
    pd.testing.assert_frame_equal(sweep.run_in_process(), df)  # the same rows as one sweep without a break


def test_without_resume_a_sweep_starts_afresh(tiny: tuple[str, Path], tmp_path: Path) -> None:
    out = tmp_path / "results.parquet"
    _sweep(tiny, [{"mode": "ok", "parts": 1}]).run_in_process(output=out)
    df = _sweep(tiny, [{"mode": "ok", "parts": 2}]).run_in_process(output=out)
    assert list(pd.read_parquet(out)["parts"]) == list(df["parts"]) == [2]


# -- the plot -------------------------------------------------------------------------------------------


def test_the_plot_is_a_line_for_one_parameter_and_a_heat_map_for_two() -> None:
    df = pd.DataFrame({"interval": [0.2, 0.2, 1.0, 1.0], "speed": [20, 80, 20, 80], "end_time": [4.0, 2.0, 6.0, 3.0]})
    line = Sweep.plot(df, "end_time", "interval")
    [ax] = line.axes
    assert list(ax.lines[0].get_ydata()) == [3.0, 4.5]  # the mean over the speeds, per interval
    assert len(ax.collections) == 1  # and the band from the lowest to the highest
    heat = Sweep.plot(df, "end_time", "interval", "speed")
    assert heat.axes[0].images[0].get_array().tolist() == [[4.0, 6.0], [2.0, 3.0]]
    assert heat.__class__.__module__ == "matplotlib.figure"  # not pyplot's: a notebook shows it once
    with pytest.raises(KeyError, match="no column 'cycle'"):
        Sweep.plot(df, "cycle", "interval")


# -- the command's refusals (before any cluster starts) ------------------------------------------------


def test_the_command_refuses_what_it_cannot_use_before_any_run(tiny: tuple[str, Path], tmp_path: Path,
                                                               capsys: pytest.CaptureFixture[str],
                                                               monkeypatch: pytest.MonkeyPatch) -> None:
    import sys

    from gpltest import in_process

    project, setup = tiny
    params = tmp_path / "p.toml"
    params.write_text('[grid]\nmode = ["ok"]\nparts = [1, 2]\n')
    out = str(tmp_path / "r.parquet")
    missing = in_process(capsys, "sweep", project, "--params", str(tmp_path / "none.toml"), "-o", out)
    assert missing.returncode == 2 and "error GPL9001" in missing.stderr and "none.toml: No such file" in missing.stderr
    bad_setup = tmp_path / "bad.py"
    bad_setup.write_text("def setup(sim, params):\n    return (\n")
    broken = in_process(capsys, "sweep", project, "--params", str(params), "--setup", str(bad_setup), "-o", out)
    assert broken.returncode == 2 and f"setup {bad_setup}:2:" in broken.stderr
    plot = in_process(capsys, "sweep", project, "--params", str(params), "--setup", str(setup), "-o", out,
                      "--plot", str(tmp_path / "p.png"), "--quiet")
    assert plot.returncode == 0 and (tmp_path / "p.png").read_bytes()[:4] == b"\x89PNG"
    params.write_text('[grid]\nmode = ["ok"]\nparts = [1, 2]\n[plot]\nx = "speed"\n')
    wrong = in_process(capsys, "sweep", project, "--params", str(params), "-o", out, "--plot", str(tmp_path / "p.png"))
    assert wrong.returncode == 2 and "--plot: 'speed' is not a parameter (the parameters: mode, parts)" in wrong.stderr
    monkeypatch.setitem(sys.modules, "pyarrow", None)  # as if gpl2py[sweep] were not installed
    extra = in_process(capsys, "sweep", project, "--params", str(params), "-o", out)
    assert extra.returncode == 2
    assert "gpl2py sweep needs pyarrow, which is not installed: pip install 'gpl2py[sweep]'" in extra.stderr


def test_a_project_with_errors_is_status_1_with_its_diagnostics(tmp_path: Path,
                                                                capsys: pytest.CaptureFixture[str]) -> None:
    from gpltest import in_process, write_project

    project = write_project(tmp_path, {"Main.gpl": "Module Main\n    Public Sub Main()\n        x = \n"
                                                   "    End Sub\nEnd Module\n"})
    params = tmp_path / "p.csv"
    params.write_text("a\n1\n")
    done = in_process(capsys, "sweep", project, "--params", str(params), "-o", str(tmp_path / "r.parquet"))
    assert done.returncode == 1 and "Main.gpl:3:" in done.stderr and "error GPL" in done.stderr
    assert not (tmp_path / "r.parquet").exists()
