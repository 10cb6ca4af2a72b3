"""Transpiled GPL that stops threads blocked on sockets: the shapes real servers use to shut down.

A server thread usually sits in ``listener.AcceptSocket()`` or ``sock.Receive(...)``; the main
thread ends it with ``Thread.Abort`` or by stopping the listener.  Before waits were made
interruptible, both programs below never ended (the run had to be killed).
"""

from __future__ import annotations

import importlib
import socket
import sys
import threading
import time
from pathlib import Path

from gpltest import RunResult, free_port, run_gpl, transpile_to
from gplrt.sim import Simulation

LIMIT = 10.0  # real seconds; each program takes well under one


def _run_to_the_end(tmp_path: Path, src: str) -> RunResult:
    """``run_gpl`` in a daemon thread: a program that never ends (the failure these tests name)
    fails the test after ``LIMIT`` instead of hanging the suite.  No wall-time assertion beyond
    that bound: how fast the threads end is the runtime's Abort grace, checked by the output."""
    box: list[RunResult] = []
    runner = threading.Thread(target=lambda: box.append(run_gpl(tmp_path, src)), daemon=True)
    runner.start()
    runner.join(LIMIT)
    assert not runner.is_alive(), "the program never ended"
    assert box, "run_gpl raised (see the thread's traceback above)"
    return box[0]


def test_abort_a_server_thread_blocked_in_accept_socket(tmp_path: Path) -> None:
    port = free_port()
    src = f"""Module Main
    Public lst As TcpListener
    Public Sub Main()
        Dim t As New Thread("Main.Server")
        t.Start()
        Thread.Sleep(300)
        Console.WriteLine("before abort " & CStr(t.ThreadState))
        t.Abort()
        Console.WriteLine("after abort " & CStr(t.ThreadState))
        lst.Stop()
        Console.WriteLine("done")
    End Sub
    Public Sub Server()
        Dim ep As New IPEndPoint("", {port})
        Dim s As Socket
        Dim ex As Exception
        lst = New TcpListener(ep)
        lst.Start()
        Try
            s = lst.AcceptSocket()
            Console.WriteLine("accepted")
        Catch ex
            Console.WriteLine("caught " & CStr(ex.ErrorCode))   ' an Abort is not an error
        Finally
            Console.WriteLine("server finally")
        End Try
    End Sub
End Module
"""
    result = _run_to_the_end(tmp_path, src)
    assert result.output.splitlines() == [
        "before abort 1", "server finally", "after abort 0", "done"]
    assert result.status == 0


def test_stopping_the_listener_wakes_the_accepting_thread_with_1707(tmp_path: Path) -> None:
    port = free_port()
    src = f"""Module Main
    Public lst As TcpListener
    Public Sub Main()
        Dim ep As New IPEndPoint("", {port})
        Dim t As New Thread("Main.Server")
        lst = New TcpListener(ep)
        lst.Start()
        t.Start()
        Thread.Sleep(200)
        lst.Stop()
        If t.Join(5000) Then Console.WriteLine("joined")
    End Sub
    Public Sub Server()
        Dim s As Socket
        Dim ex As Exception
        Try
            s = lst.AcceptSocket()
        Catch ex
            Console.WriteLine("accept ended " & CStr(ex.ErrorCode))
        End Try
    End Sub
End Module
"""
    result = _run_to_the_end(tmp_path, src)
    assert result.output.splitlines() == ["accept ended -1707", "joined"]


CELL = """Module Cell
    Public lst As TcpListener
    Public conn_thread As Thread
    Public Sub Main()
        Dim ep As New IPEndPoint("", PORT)
        Dim server As New Thread("Server")
        lst = New TcpListener(ep)
        lst.Start()
        server.Start()
        Console.WriteLine("listening")
        While Not Signal.DIO(10001)          ' the operator's stop button
            Thread.Sleep(50)
        End While
        server.Abort()
        If Not conn_thread Is Nothing Then conn_thread.Abort()
        lst.Stop()
        Console.WriteLine("stopped " & CStr(server.ThreadState) & " " & CStr(conn_thread.ThreadState))
    End Sub
    Sub Server()
        Dim s As Socket
        Do
            s = lst.AcceptSocket()
            Handler.pending = s
            conn_thread = New Thread("Handler.Serve")
            conn_thread.Start()
        Loop
    End Sub
End Module
"""

HANDLER = """Module Handler
    Public pending As Socket
    Public Sub Serve()
        Dim s As Socket
        Dim buf As String
        s = pending
        Try
            Do
                If s.Receive(buf, 100) = 0 Then Exit Do
                s.Send("pong " & buf.Trim() & Chr(13) & Chr(10))
            Loop
        Finally
            s.Close()
            Console.WriteLine("connection closed")
        End Try
    End Sub
End Module
"""


def test_a_stop_button_aborts_a_server_blocked_in_accept_and_a_handler_in_receive(tmp_path: Path) -> None:
    """Signals, threads and sockets together, on the virtual clock: a client is served, then an
    input ends the cell; the handler's Finally closes the client's connection."""
    port = free_port()
    package, _, _ = transpile_to(tmp_path, {"Cell.gpl": CELL.replace("PORT", str(port)), "Handler.gpl": HANDLER},
                                 start="Main")
    sys.path.insert(0, str(tmp_path / "out"))
    try:
        pkg = importlib.import_module(package)
    finally:
        sys.path.remove(str(tmp_path / "out"))
    sim = Simulation(capture=True)
    runner = threading.Thread(target=pkg.main, args=(sim,), daemon=True)
    runner.start()
    deadline = time.monotonic() + LIMIT
    while "listening" not in sim.console.output and time.monotonic() < deadline:
        time.sleep(0.02)
    client = socket.create_connection(("127.0.0.1", port), timeout=LIMIT)
    try:
        client.sendall(b"ping\n")
        assert client.recv(100) == b"pong ping\r\n"
        sim.io.set_input(10001, True)
        runner.join(LIMIT)
        assert not runner.is_alive()
        assert client.recv(100) == b""  # the aborted handler's Finally closed the connection
    finally:
        client.close()
    assert sim.console.output.splitlines() == ["listening", "connection closed", "stopped 0 0"]
    assert sim.controller.error_log == []
