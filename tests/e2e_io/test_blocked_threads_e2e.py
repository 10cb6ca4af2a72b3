"""Transpiled GPL that stops threads blocked on sockets: the shapes real servers use to shut down.

A server thread usually sits in ``listener.AcceptSocket()`` or ``sock.Receive(...)``; the main
thread ends it with ``Thread.Abort`` or by stopping the listener.  Before waits were made
interruptible, both programs below never ended (the run had to be killed).
"""

from __future__ import annotations

import time
from pathlib import Path

from gpltest import free_port, run_gpl

LIMIT = 10.0  # real seconds; each program takes well under one


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
    start = time.monotonic()
    result = run_gpl(tmp_path, src)
    assert time.monotonic() - start < LIMIT
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
    start = time.monotonic()
    result = run_gpl(tmp_path, src)
    assert time.monotonic() - start < LIMIT
    assert result.output.splitlines() == ["accept ended -1707", "joined"]
