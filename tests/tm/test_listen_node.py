"""The Listen node's replies, byte for byte as the manual prints them (§14, L17642-L18305), and
bad packets that each get the manual's reply and leave the node serving the next one."""

from __future__ import annotations

import pytest
from tmpacket import NodeClient as Client

from gplrt.tm.packets import encode


@pytest.fixture
def client(tm_robot):  # type: ignore[no-untyped-def]
    c = Client(tm_robot[1].port)
    yield c
    c.close()


def wait_until(condition, limit: float = 30.0) -> None:  # type: ignore[no-untyped-def]
    """Wait for the node to reach a state (not a timing assertion: the limit only ends a hang)."""
    import time

    end = time.monotonic() + limit
    while not condition():
        assert time.monotonic() < end, "the node never reached the state"
        time.sleep(0.005)


def script(ident: str, text: str) -> bytes:
    return encode("TMSCT", f"{ident},{text}".encode())


def test_the_manual_packets_and_replies(client) -> None:  # type: ignore[no-untyped-def]
    # L17823-L17824: a script and its OK, with the manual's checksums
    assert client.ask(b'$TMSCT,25,1,ChangeBase("RobotBase"),*08\r\n') == b"$TMSCT,4,1,OK,*5C\r\n"
    # L17841-L17851: locals live between packets; declaring one again is an error on line 1
    assert client.ask(b"$TMSCT,40,3,int var_i = 100\r\nvar_i = 1000\r\nvar_i++,*5A\r\n") == b"$TMSCT,4,3,OK,*5E\r\n"
    assert client.ask(b"$TMSCT,42,4,int var_i = 100\r\nvar_i = 1000\r\nvar_i++\r\n,*58\r\n") == b"$TMSCT,9,4,ERROR;1,*02\r\n"
    # L17902, L17925: TMSTA 00 in listen mode; L17986-L17990: tag 15 and 88 do not exist
    assert client.ask(b"$TMSTA,2,00,*41\r\n") == b"$TMSTA,15,00,true,Listen1,*79\r\n"
    assert client.ask(b"$TMSTA,5,01,15,*6F\r\n") == b"$TMSTA,10,01,15,none,*7D\r\n"
    assert client.ask(b"$TMSTA,5,01,88,*6B\r\n") == b"$TMSTA,10,01,88,none,*79\r\n"


def test_status_query_forms_and_lower_case_checksums(client) -> None:  # type: ignore[no-untyped-def]
    assert client.ask(encode("TMSTA", b"00,")) == b"$TMSTA,15,00,true,Listen1,*79\r\n"
    lower = b'$TMSCT,25,1,ChangeBase("RobotBase"),*08\r\n'.replace(b"*08", b"*08")
    assert client.ask(lower) == b"$TMSCT,4,1,OK,*5C\r\n"
    frame = script("7", "int k = 1")
    cs = frame[-4:-2]
    assert client.ask(frame[:-4] + cs.lower() + b"\r\n") == encode("TMSCT", b"7,OK")


@pytest.mark.parametrize("packet, reply", [
    (b'$TMSCT,-100,1,ChangeBase("RobotBase"),*13\r\n', b"$CPERR,2,01,*49\r\n"),  # L18093
    (b'$TMSCT,30,1,ChangeBase("RobotBase"),*08\r\n', b"$CPERR,2,01,*49\r\n"),  # length beyond the data
    (b'$TMSCT,25,1,ChangeBase("RobotBase"),*09\r\n', b"$CPERR,2,02,*4A\r\n"),  # L18100
    (b'$TMsct,25,1,ChangeBase("RobotBase"),*28\r\n', b"$CPERR,2,03,*4B\r\n"),  # L18107
    (b"$TMSTA,4,XXXX,*47\r\n", b"$CPERR,2,04,*4C\r\n"),  # L18114
    (encode("TMSCT", b'a-1,ChangeBase("RobotBase")'), b"$CPERR,2,04,*4C\r\n"),  # L17787: the id
    (encode("TMSCT", b"5,int a = \r\nint b = 2\r\nPTP(\"JPP\",0,0,90,0,90,0,10,200,0,false"),
     encode("TMSCT", b"5,ERROR;1;3")),  # syntax errors on lines 1 and 3
    (encode("TMSCT", b"6,int z = 0\r\nint y = 5\r\ny = y / z"), encode("TMSCT", b"6,ERROR;3")),
    (encode("TMSCT", b"8,int w = 5 / 0"), encode("TMSCT", b"8,ERROR;1")),
    (encode("TMSCT", b"9,string s = Hello"), encode("TMSCT", b"9,OK;1")),  # a warning (L602)
])
def test_bad_packets_get_the_manual_reply_and_the_node_serves_on(client, packet, reply) -> None:  # type: ignore[no-untyped-def]
    assert client.ask(packet) == reply
    assert client.ask(script("10", "int after = 1\r\nafter++")) == encode("TMSCT", b"10,OK")


def test_greeting_on_entry_and_cperr_f1_after_script_exit(tm_robot) -> None:  # type: ignore[no-untyped-def]
    robot, node, _ = tm_robot
    c = Client(node.port)
    try:
        assert c.ask(b"$TMSTA,2,00,*41\r\n") == b"$TMSTA,15,00,true,Listen1,*79\r\n"
        assert c.ask(script("1", "ChangeTCP(\"NOTOOL\")\r\nScriptExit()\r\nChangeLoad(10.1)")) == encode("TMSCT", b"1,OK")
        node.exited.wait(10)
        assert robot.load == 0.0  # ChangeLoad after ScriptExit() is not executed (L17690)
        assert c.ask(b'$TMSCT,25,1,ChangeBase("RobotBase"),*08\r\n') == b"$CPERR,2,F1,*3F\r\n"  # L18121
        assert c.ask(b"$TMSTA,2,00,*41\r\n") == b"$TMSTA,9,00,false,,*37\r\n"  # L17895
        node.enter()
        assert c.reply() == b"$TMSCT,9,0,Listen1,*4C\r\n"  # L17800
        assert c.ask(b'$TMSCT,25,1,ChangeBase("RobotBase"),*08\r\n') == b"$TMSCT,4,1,OK,*5C\r\n"
    finally:
        c.close()


def test_queue_tag_pushed_when_done_and_priority_commands(tm_robot) -> None:  # type: ignore[no-untyped-def]
    robot, node, _ = tm_robot
    c = Client(node.port)
    try:
        assert c.ask(script("1", 'PTP("JPP",0,0,90,0,90,0,10,200,0,false)\r\nQueueTag(2)')) == encode("TMSCT", b"1,OK")
        assert c.reply() == b"$TMSTA,10,01,02,true,*67\r\n"  # L18269: pushed when tag 2 is done
        assert c.ask(encode("TMSTA", b"01,02")) == encode("TMSTA", b"01,02,true")
        # a priority command with a variable is a syntax error (L18186-L18190)
        assert c.ask(b"$TMSCT,42,1,int var_st=2\r\nStopAndClearBuffer(var_st),*3A\r\n") == b"$TMSCT,9,1,ERROR;2,*04\r\n"
        # a packet with priority commands runs only the first ScriptExit (L18200-L18216)
        assert c.ask(script("4", "StopAndClearBuffer(2)\r\nStopAndClearBuffer(1)\r\nScriptExit(1)")) == encode("TMSCT", b"4,OK")
        assert node.exited.wait(10) and node.result == "pass"
    finally:
        c.close()


def test_listen_send_pushes_the_manuals_bytes(client) -> None:  # type: ignore[no-untyped-def]
    # L18040-L18064: ListenSend(90, "Hello World"), (91, float[] {1,2,3,4}), (92, byte[] {0x10..0x13})
    sent = script("1", 'string var_s = "Hello World"\r\nfloat[] var_f = {1,2,3,4}\r\n'
                       "byte[] var_b = {0x10, 0x11, 0x12, 0x13}\r\nListenSend(90, var_s)\r\n"
                       "ListenSend(91, var_f)\r\nListenSend(92, var_b)")
    client.send(sent)
    assert client.reply() == b"$TMSTA,14,90,Hello World,*73\r\n"
    frame = client.reply()
    assert frame == b"$TMSTA,19,91," + bytes.fromhex("0000803F000000400000404000008040") + b",*60\r\n"
    assert client.reply() == b"$TMSTA,7,92,\x10\x11\x12\x13,*63\r\n"
    assert client.reply() == encode("TMSCT", b"1,OK")


def test_a_priority_command_ends_a_script_that_loops_forever(tm_robot) -> None:  # type: ignore[no-untyped-def]
    _, node, _ = tm_robot
    c = Client(node.port)
    other = Client(node.port)
    try:
        c.send(script("1", "int n = 0\r\nwhile (true)\r\n{\r\n  n++\r\n}"))
        c.send(script("2", "int m = 5"))  # queued behind the looping script
        wait_until(lambda: node.running is not None and len(node.jobs) == 1)
        assert other.ask(script("3", "StopAndClearBuffer(1)")) == encode("TMSCT", b"3,OK")
        assert c.reply() == encode("TMSCT", b"1,OK")  # abandoned (L18252: it answers OK)
        assert c.reply() == encode("TMSCT", b"2,OK")  # and the next script runs
        assert other.ask(script("4", "m++")) == encode("TMSCT", b"4,OK")
    finally:
        c.close()
        other.close()


def test_garbage_and_hostile_scripts_leave_the_node_serving(client, tm_robot) -> None:  # type: ignore[no-untyped-def]
    import random

    rng = random.Random(22)
    client.send(bytes(rng.randrange(256) for _ in range(5000)) + b"\r\n")
    client.send(script("99", "int sync = 1"))
    while (frame := client.reply()) != encode("TMSCT", b"99,OK"):
        assert frame.startswith(b"$CPERR,2,0"), frame  # what the garbage earned, if anything
    hostile = [
        '__import__("os").system("echo owned")', "int x = 1\r\nx = x" + " + 1" * 2000, '"\\x00\\"""',
        "while (true)", "string s = \"" + "a" * 100000 + "\"", "Display(" * 500, "int a[] = 1",
        "Robot[1].Joint", "IO[\"Nope\"].DO[0] = 1", 'PTP("JPP",0,0,900,0,90,0,50,200,0,false)',
    ]
    for i, text in enumerate(hostile):
        client.send(script(str(100 + i), text))
        while (reply := client.reply()).startswith(b"$TMSTA,"):
            pass  # (the tag the last script queued)
        assert reply.startswith(f"$TMSCT,".encode()) and (b",OK" in reply or b",ERROR;" in reply), reply[:200]
    # an unreachable target stops the project by error (tests/tm/test_tm_motion.py): the node is
    # left, and serves again once the flow enters it anew
    robot, node, _ = tm_robot
    assert client.ask(script("120", 'PTP("CPP",5000,0,0,0,0,0,50,200,0,false)')) == encode("TMSCT", b"120,OK")
    robot.wait_idle()
    assert client.ask(script("121", "int x = 1")) == encode("CPERR", b"F1")
    node.enter()
    assert client.reply() == encode("TMSCT", b"0,Listen1")
    client.send(script("1", "int alive = 1"))
    while (reply := client.reply()).startswith(b"$TMSTA,"):
        pass
    assert reply == encode("TMSCT", b"1,OK")
