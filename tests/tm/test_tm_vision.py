"""TMvision on the simulated robot (issue 22, item 4): the vision functions (L17229-L17641) and
``File_GetImage``/``File_CopyImage`` (L11737-L11895) on a backend the test fills as a notebook
would (``robot.vision.register``).  A job nobody registered is one the project does not have:
running it fails (false, L17247)."""

from __future__ import annotations

import pytest
from tmpacket import run_packet

from gplrt.tm import context
from gplrt.tm.values import TMError

BLOBS = "job1_Count_Blob_1_DetectObjectX_TM"
PNG = b"\x89PNG\r\n\x1a\n source"


@pytest.fixture
def robot():  # type: ignore[no-untyped-def]
    return context.use_robot("TM5-900")


def test_a_job_nobody_registered_fails_to_execute(robot) -> None:  # type: ignore[no-untyped-def]
    v = run_packet('bool a = Vision_IsJobAvailable("job1")\r\nbool r = Vision_DoJob("job1")\r\n'
                   'bool p = Vision_DoJob_PTP("job1", 100, 500)\r\nbool l = Vision_DoJob_Line("job1", 100)\r\n'
                   'string[] img = File_GetImage(0)')
    assert (v.a, v.r, v.p, v.l) == (False, False, False, False)
    assert list(v.img) == ["", ""]  # no image path in the buffer


def test_registered_results_outputs_and_the_manuals_arrays_l17469(robot) -> None:  # type: ignore[no-untyped-def]
    robot.vision.register("job1", passed=True, outputs={BLOBS: [["0", "1", "2"], ["3", "4"], ["5"]]})
    robot.vision.register("job1", passed=False, outputs={BLOBS: []})
    v = run_packet(f'bool a = Vision_IsJobAvailable("job1")\r\nbool r = Vision_DoJob("job1")\r\n'
                   f'int var_count = Vision_GetOutputArraySize("{BLOBS}")\r\n'
                   f'int var_length = Vision_GetOutputArraySize("{BLOBS}", 1)\r\n'
                   f'string[] var_ss = Vision_GetOutputArrayValue("{BLOBS}", 0)\r\n'
                   f'string var_s = Vision_GetOutputArrayValue("{BLOBS}", 2, 0)\r\n'
                   f'bool r2 = Vision_DoJob("job1")\r\nint n2 = Vision_GetOutputArraySize("{BLOBS}")\r\n'
                   f'bool r3 = Vision_DoJob("job1")')
    assert (v.a, v.r, v.var_count, v.var_length, list(v.var_ss), v.var_s) == (True, True, 3, 2, ["0", "1", "2"], "5")
    assert (v.r2, v.n2, v.r3) == (False, 0, False)  # the second result, then the last one again
    robot.vision.register("job2", outputs={BLOBS: [["0", "1", "2"], ["3", "4"], ["5"]]})
    with pytest.raises(TMError, match=r"Exceeded the access range \(find object count: 3, index: 0 \.\. 2\)"):
        run_packet(f'bool r = Vision_DoJob("job2")\r\nstring var_se = Vision_GetOutputArrayValue("{BLOBS}", 3, 0)')


def test_a_job_with_an_initial_position_moves_there_in_the_queue_first_l17262(robot) -> None:  # type: ignore[no-untyped-def]
    home = robot.arm.fk([0.0, 0.0, 90.0, 0.0, 90.0, 0.0])
    spot = [home[0] + 50.0, home[1] - 40.0, home[2] - 30.0, *home[3:]]
    robot.vision.register("pick", passed=True, initial=spot, base=[10, 20, 30, 0, 0, 90])
    v = run_packet('bool r0 = Vision_DoJob("pick")\r\n'  # (a job with an initial position: false)
                   'PTP("JPP",0,0,90,0,90,0,50,200,0,false)\r\n'
                   'bool r = Vision_DoJob_PTP("pick", 50, 200)\r\n'
                   'float[] b = Base["vision_pick"].Value')
    assert v.r0 is False and v.r is True
    assert robot.arm.fk(robot.joints) == pytest.approx(spot, abs=1e-6)  # it ran at its initial position
    assert list(v.b) == [10, 20, 30, 0, 0, 90]  # the vision base the job updated
    robot.vision.jobs["pick"].initial = home
    assert run_packet('bool r = Vision_DoJob_Line("pick", 100, 300)').r is True
    assert robot.arm.fk(robot.joints) == pytest.approx(home, abs=1e-6)


def test_trigger_job_buffer_l17572(robot) -> None:  # type: ignore[no-untyped-def]
    for row in (["0", "1", "2"], ["3", "4"], ["5"]):
        robot.vision.trigger(BLOBS, row)
    v = run_packet(f'int c0 = Vision_GetTriggerJobOutputCount("{BLOBS}")\r\n'
                   f'string[] s1 = Vision_GetTriggerJobOutputValue("{BLOBS}")\r\n'
                   f'int c1 = Vision_GetTriggerJobOutputCount("{BLOBS}")\r\n'
                   f'string[] s2 = Vision_GetTriggerJobOutputValue("{BLOBS}")\r\n'
                   f'string[] s3 = Vision_GetTriggerJobOutputValue("{BLOBS}")\r\n'
                   f'string[] s4 = Vision_GetTriggerJobOutputValue("{BLOBS}")\r\n'
                   f'int c4 = Vision_GetTriggerJobOutputCount("{BLOBS}")')
    assert (v.c0, list(v.s1), v.c1, list(v.s2), list(v.s3), list(v.s4), v.c4) == \
        (3, ["0", "1", "2"], 2, ["3", "4"], ["5"], [], 0)


def test_images_are_saved_popped_and_copied_to_the_usb_drive_only_l11737(robot) -> None:  # type: ignore[no-untyped-def]
    robot.vision.register("Job1", passed=True, source_image=PNG, result_image=b"result")
    v = run_packet('bool r = Vision_DoJob("Job1")\r\nstring[] var_image = File_GetImage()\r\n'
                   'bool local = File_CopyImage(var_image[0], ".\\TextFiles", "1.png")\r\n'
                   'bool local2 = File_CopyImage(var_image[0], ".\\XmlFiles", "1.png", 2)\r\n'
                   'bool usb = File_CopyImage(var_image[0], "\\USB\\TMROBOT", "1.png")\r\n'
                   'bool kept = File_CopyImage(var_image[1], "\\USB\\TMROBOT", 3)\r\n'
                   'bool plain = File_CopyImage(var_image[0], "\\USB\\TMROBOT")\r\n'
                   'bool missing = File_CopyImage("\\Vision\\nothing.png", "\\USB\\TMROBOT")\r\n'
                   'string[] none = File_GetImage(100)')
    assert v.r is True
    source, result = list(v.var_image)
    assert source.startswith("\\Vision\\") and "\\Job1\\" in source and "\\source\\" in source
    assert (v.local, v.local2, v.usb, v.kept, v.plain, v.missing) == (False, False, True, True, True, False)
    box = robot.sim.files.root().box
    assert box.path("USB", "1.png").read_bytes() == PNG
    stamp = source.split("\\")[-1]
    assert box.path("USB", stamp).read_bytes() == PNG  # the source's own name
    kept = result.split("\\")[2:]  # (Vision\<project>\Job1\<date>\result\<stamp>: the folders kept)
    assert box.path("USB", *kept).read_bytes() == b"result"
    assert box.path("TextFiles", "1.png").lstat() is None
    assert list(v.none) == ["", ""]  # the buffer is empty: after 100 ms, nothing
    with pytest.raises(TMError, match="does not exist"):  # option 2: an error when the copy fails
        run_packet('bool b = File_CopyImage("\\Vision\\nothing.png", "\\USB\\TMROBOT", 2)')
    with pytest.raises(TMError, match="not a saved vision image"):  # (never a path outside the images)
        run_packet('bool b = File_CopyImage("\\TextFiles\\..\\..\\secret", "\\USB\\TMROBOT", 2)')


def test_vpoint_reads_and_moves_a_jobs_initial_position_l14559(robot) -> None:  # type: ignore[no-untyped-def]
    home = robot.arm.fk([0.0, 0.0, 90.0, 0.0, 90.0, 0.0])
    robot.vision.register("Job1", initial=home)
    v = run_packet('float[] f = VPoint["Job1"].Value\r\nfloat f0 = VPoint["Job1"].Value[0]\r\n'
                   'string s = VPoint["Job1"].BaseName\r\n'
                   'VPoint["Job1"].Value[2] = 120\r\nfloat z = VPoint["Job1"].Value[2]\r\n'
                   'float[] t = VPoint["Job1"].TeachValue')
    assert list(v.f) == pytest.approx(home, abs=1e-4) and v.f0 == pytest.approx(home[0], abs=1e-4)
    assert (v.s, v.z) == ("RobotBase", 120.0)
    assert robot.vision.jobs["Job1"].initial[2] == 120.0  # the job now starts there
    assert list(v.t) == pytest.approx(home, abs=1e-4)  # the position it was taught
    with pytest.raises(TMError):
        run_packet('float f6 = VPoint["Job1"].Value[6]')  # (exceeding the array's access range)
    with pytest.raises(TMError, match='VPoint\\["nojob"\\] does not exist'):
        run_packet('float[] g = VPoint["nojob"].Value')


def test_an_element_written_through_a_points_value_reaches_the_point_l14445(robot) -> None:  # type: ignore[no-untyped-def]
    v = run_packet('TPoint p1 = 400, 0, 300, 180, 0, 90\r\nPoint["p1"].Value[2] = 120\r\nfloat z = Point["p1"].Value[2]\r\n'
                   'TBase b1 = 1, 2, 3, 4, 5, 6\r\nb1.Value[4] = 120\r\nfloat ry = Base["b1"].Value[4]\r\n'
                   'TTCP t1 = 0, 0, 100, 0, 0, 0\r\nTCP["t1"].Value[0] = 10\r\nfloat x = t1.Value[0]')
    assert (v.z, v.ry, v.x) == (120.0, 120.0, 10.0)  # (before: 300, 5, 0: the write was lost)
