"""End-to-end: small GPL programs, transpiled, run on gplrt.sim, exact Console output asserted."""

from __future__ import annotations

from pathlib import Path

import pytest

from gpltest import module_src, run_gpl


def run_main(tmp_path: Path, body: str, decls: str = "") -> str:
    src = module_src(f"{decls}\n    Public Sub Main()\n{body}\n    End Sub")
    result = run_gpl(tmp_path, src)
    assert result.log == "", result.log
    return result.output


CASES: dict[str, tuple[str, str, str]] = {
    # name: (declarations, Main body, expected output)
    "half_rounds_away_from_zero": (
        "",
        """        Dim i, j, k As Integer
        Dim b As Byte
        Dim d As Double
        d = 2.5
        i = d
        d = -2.5
        j = d
        k = 3.49
        b = 0.5
        Console.WriteLine(i & " " & j & " " & k & " " & b & " " & CInt(-0.5) & " " & CShort(1.5))""",
        "3 -3 3 1 -1 2\n",
    ),
    "boolean_is_minus_one": (
        "",
        """        Dim b As Boolean
        Dim i As Integer
        b = True
        i = b
        Console.WriteLine(i)
        Console.WriteLine(b + 1)
        Console.WriteLine(True And 6)
        Console.WriteLine(True And False)
        Console.WriteLine(5 Or 2)
        Console.WriteLine(Not 5)
        Console.WriteLine(Not 0)
        Console.WriteLine(True < False)""",
        "-1\n0\n6\n0\n7\n0\n-1\n-1\n",
    ),
    "arithmetic_operators": (
        "",
        """        Console.WriteLine(5 / 2)
        Console.WriteLine(7 \\ 2)
        Console.WriteLine(2.3 \\ 2)
        Console.WriteLine(-7 \\ 2)
        Console.WriteLine(13.3 Mod 2)
        Console.WriteLine(-7 Mod 3)
        Console.WriteLine(2 ^ 10)
        Console.WriteLine(1 << 4)
        Console.WriteLine(-16 >> 2)
        Console.WriteLine(1 / 3)
        Console.WriteLine(10.2)""",
        "2.5\n3\n1\n-3\n1.3\n-1\n1024\n16\n-4\n0.333333333333333\n10.2\n",
    ),
    "string_number_plus": (
        "",
        """        Dim s As String
        Dim d As Double
        d = 2.34 + "1.01"
        Console.WriteLine(d)
        Console.WriteLine("1.01" + 2.34)
        Console.WriteLine("ab" + "cd")
        s = 5
        s = s & 1.5 & True
        Console.WriteLine(s)
        Console.WriteLine("A" < "a")
        Console.WriteLine("abc" = "ABC")""",
        "3.35\n3.35\nabcd\n51.5-1\n-1\n0\n",
    ),
    "string_members_and_functions": (
        "",
        """        Dim s As String
        s = "Hello World"
        Console.WriteLine(s.Length & " " & s.Substring(6, 5) & " " & s.IndexOf("o") & " " & s.ToUpper())
        Console.WriteLine(Mid(s, 1, 5) & " " & InStr(1, s, "World") & " " & Len(s) & " " & LCase(s))
        Console.WriteLine(Chr(65) & Asc("a") & " " & Format(3.14159, "0.00") & " " & String.Compare("a", "b"))""",
        "11 World 4 HELLO WORLD\nHello 7 11 hello world\nA97 3.14 -1\n",
    ),
    "if_elseif_single_line": (
        "",
        """        Dim n As Integer
        For n = 1 To 4
            If n = 1 Then Console.Write("one ") Else Console.Write("many ")
            If n < 2 Then
                Console.WriteLine("small")
            ElseIf n < 3 Then
                Console.WriteLine("medium")
            ElseIf n = 3 Then
                Console.WriteLine("three")
            Else
                Console.WriteLine("big")
            End If
        Next""",
        "one small\nmany medium\nmany three\nmany big\n",
    ),
    "select_lists_ranges_is": (
        "",
        """        Dim n As Integer
        Dim c As String
        For n = 0 To 12 Step 3
            Select Case n
                Case 1, 3, 5
                    Console.WriteLine(n & " odd small")
                Case 6 To 9
                    Console.WriteLine(n & " range")
                Case Is > 10
                    Console.WriteLine(n & " big")
                Case Else
                    Console.WriteLine(n & " else")
            End Select
        Next
        c = "red"
        Select c
            Case "blue", "re" & "d"
                Console.WriteLine("colour")
                Exit Select
                Console.WriteLine("never")
        End Select""",
        "0 else\n3 odd small\n6 range\n9 range\n12 big\ncolour\n",
    ),
    "for_next_semantics": (
        "",
        """        Dim i, n As Integer
        Dim d As Double
        Dim a(3) As Integer
        n = 3
        For i = 1 To n
            n = 10
        Next
        Console.WriteLine("i=" & i & " n=" & n)
        For i = 10 To 1 Step -3
            Console.Write(i & " ")
        Next i
        Console.WriteLine(i)
        For d = 0 To 1 Step 0.25
            Console.Write(d & " ")
        Next
        Console.WriteLine(d)
        For i = 5 To 1
            Console.WriteLine("never")
        Next
        Console.WriteLine(i)
        For i = 0 To 3
            i = i + 1
            Console.Write(i)
        Next
        Console.WriteLine("")
        For a(1) = 1 To 3
        Next
        Console.WriteLine(a(1))""",
        "i=4 n=10\n10 7 4 1 -2\n0 0.25 0.5 0.75 1 1.25\n5\n13\n4\n",
    ),
    "loops_and_exits": (
        "",
        """        Dim i, j As Integer
        i = 0
        While True
            i += 1
            If i = 3 Then Exit While
        End While
        Do While i < 6
            i += 1
        Loop
        Do Until i >= 8
            i += 1
        Loop
        Do
            i += 1
        Loop While i < 10
        Do
            i += 1
        Loop Until i >= 12
        Do
            i += 1
            If i = 14 Then Exit Do
        Loop
        Console.WriteLine(i)
        For i = 1 To 3
            j = 0
            Do
                j += 1
                If j = 2 Then Exit For
            Loop
        Next
        Console.WriteLine(i & " " & j)
        For Each j In New Integer() {}
        Next""",
        "",  # replaced below (For Each over a literal is not GPL)
    ),
    "arrays": (
        "",
        """        Dim a(4) As Integer
        Dim b() As Integer
        Dim m(2, 3) As Double
        Dim s(1) As String
        Dim i As Integer
        For i = 0 To a.GetUpperBound(0)
            a(i) = i * i
        Next
        b = a
        b(0) = 42
        Console.WriteLine(a(0) & " " & a.Length & " " & a.Rank & " " & m.Length & " " & m.Rank & " " & m.GetUpperBound(1))
        m(2, 3) = 1.5
        Console.WriteLine(m(2, 3) + m(0, 0))
        Console.WriteLine("[" & s(1) & "] " & s(1).Length & " " & s.Length)
        ReDim b(1)
        Console.WriteLine(b.Length & " " & a.Length & " " & b(1))
        For Each i In a
            Console.Write(i & ",")
        Next
        Console.WriteLine("")""",
        "42 5 1 12 2 3\n1.5\n[] 0 2\n2 5 0\n42,1,4,9,16,\n",
    ),
    "static_locals_persist": (
        """    Function Counted() As Integer
        Static calls As Integer
        Static base As Integer = 100
        calls += 1
        base += 10
        Return calls * 1000 + base
    End Function""",
        """        Counted()
        Counted()
        Console.WriteLine(Counted())""",
        "3130\n",
    ),
    "function_result_by_name_and_default": (
        """    Function Twice(ByVal n As Integer) As Integer
        Twice = n * 2
        If n > 5 Then Exit Function
        Twice = Twice + 1
    End Function
    Function Nothing_Assigned() As String
    End Function
    Function Opt(ByVal a As Integer, Optional ByVal b As Integer = 7) As Integer
        Return a + b
    End Function""",
        """        Console.WriteLine(Twice(2) & " " & Twice(6) & " [" & Nothing_Assigned() & "] " & Opt(1) & " " & Opt(1, 2))""",
        "5 12 [] 8 3\n",
    ),
    "byref_aliases_element_field_module_local": (
        """    Dim counter As Integer
    Class Box
        Public v As Integer
    End Class
    Sub Bump(ByRef x As Integer)
        x += 1
    End Sub
    Sub Twice(ByRef x As Integer)
        Bump(x)
        Bump(x)
    End Sub
    Sub ByVal_Untouched(ByVal x As Integer)
        x = 100
    End Sub""",
        """        Dim arr(2) As Integer
        Dim b As New Box
        Dim k As Integer
        Bump(arr(1))
        Twice(b.v)
        Twice(counter)
        Bump(k)
        ByVal_Untouched(k)
        Bump(k + 1)
        Console.WriteLine(arr(1) & " " & b.v & " " & counter & " " & k)""",
        "1 2 2 1\n",
    ),
    "classes_fields_shared_properties_overloads": (
        """    Public Class Counter
        Public count As Integer = 10
        Public Shared made As Integer
        Private name As String
        Public Sub New()
            name = "anon"
            made += 1
        End Sub
        Public Sub New(ByVal n As String)
            name = n
            made += 1
        End Sub
        Public Sub Increment()
            count += 1
        End Sub
        Public Property Label As String
            Get
                Return name & ":" & count
            End Get
            Set(ByVal value As String)
                name = value
            End Set
        End Property
        Public Function Plus(ByVal x As Integer) As Integer
            Return Me.count + x
        End Function
        Public Class Inner
            Public z As Double = 1.5
        End Class
    End Class""",
        """        Dim c As New Counter
        Dim c2 As Counter
        Dim n As New Counter.Inner
        c.Increment
        c.Increment()
        Console.WriteLine(c.Label)
        c.Label = "first"
        c2 = New Counter("two")
        Console.WriteLine(c.Label & " " & c2.Label & " made " & Counter.made & " " & c2.Plus(5) & " " & n.z)
        c2 = c
        c2.count = 1
        Console.WriteLine(c.count & " " & (c2 Is c) & " " & (c2 Is Nothing) & " " & (Not c2 Is Nothing))""",
        "anon:12\nfirst:12 two:10 made 2 15 1.5\n1 -1 0 -1\n",
    ),
    "delegates": (
        """    Delegate Function BinOp(ByVal a As Integer, ByVal b As Integer) As Integer
    Public Function Plus(ByVal a As Integer, ByVal b As Integer) As Integer
        Return a + b
    End Function
    Class Scaler
        Public k As Integer
        Public Function Scale(ByVal a As Integer, ByVal b As Integer) As Integer
            Return (a + b) * k
        End Function
    End Class""",
        """        Dim d(2) As BinOp
        Dim s As New Scaler
        Dim name As String
        s.k = 10
        d(0) = New BinOp(AddressOf Plus)
        name = "main.PLUS"
        d(1) = New BinOp(name)
        d(2) = New BinOp(AddressOf s.Scale)
        s = New Scaler
        Console.WriteLine(d(0)(1, 2) & " " & d(1)(3, 4) & " " & d(2)(1, 1))""",
        "3 7 20\n",
    ),
    "try_finally_exit_try_and_retry": (
        "",
        """        Dim ex As Exception
        Dim tries As Integer
        Try
            Console.WriteLine("in try")
            Exit Try
            Console.WriteLine("not here")
        Catch ex
            Console.WriteLine("no")
        Finally
            Console.WriteLine("finally")
        End Try
        Try
            Try
                Throw New Exception
            Finally
                Console.WriteLine("inner finally")
            End Try
        Catch ex
            Console.WriteLine("outer catch " & ex.ErrorCode)
        End Try
        tries = 0
        Try
retry:
            tries += 1
            If tries < 3 Then
                ex = New Exception
                ex.ErrorCode = -153
                Throw ex
            End If
            Console.WriteLine("done after " & tries)
        Catch ex
            Console.WriteLine("retry after " & ex.ErrorCode)
            GoTo retry
        Finally
            Console.WriteLine("finally once")
        End Try""",
        "in try\nfinally\ninner finally\nouter catch 0\nretry after -153\nretry after -153\ndone after 3\n"
        "finally once\n",
    ),
    "runtime_faults_have_codes": (
        """    Function Divide(ByVal a As Integer, ByVal b As Integer) As Double
        Return a / b
    End Function
    Function Outer(ByVal b As Integer) As Double
        Return Divide(1, b)
    End Function
    Class K
        Public v As Integer
    End Class""",
        """        Dim ex As Exception
        Dim i As Integer
        Dim s As Short
        Dim a(2) As Integer
        Dim o As K
        Try
            Console.WriteLine(Outer(0))
        Catch ex
            Console.WriteLine("div " & ex.ErrorCode & " " & ex.Message)
        End Try
        Try
            i = 2147483647
            i = i + 1
        Catch ex
            Console.WriteLine("overflow " & ex.ErrorCode & " " & i)
        End Try
        Try
            s = 40000
        Catch ex
            Console.WriteLine("short " & ex.ErrorCode)
        End Try
        Try
            a(-1) = 3
        Catch ex
            Console.WriteLine("index " & ex.ErrorCode)
        End Try
        Try
            a(3) = 3
        Catch ex
            Console.WriteLine("index " & ex.ErrorCode)
        End Try
        Try
            o.v = 1
        Catch ex
            Console.WriteLine("nothing " & ex.ErrorCode)
        End Try
        Try
            i = "abc"
        Catch ex
            Console.WriteLine("format " & ex.ErrorCode)
        End Try
        Try
            i = 7 Mod 0
        Catch ex
            Console.WriteLine("mod " & ex.ErrorCode)
        End Try
        Dim d As Double
        d = 1E+300
        Try
            d = d * d
        Catch ex
            Console.WriteLine("double " & ex.ErrorCode & " " & d)
        End Try""",
        "div -709 *Division by 0*\noverflow -710 2147483647\nshort -710\nindex -767\nindex -767\nnothing -757\n"
        "format -717\nmod -709\ndouble -710 1E+300\n",
    ),
    "goto_out_of_three_nested_loops": (
        "",
        """        Dim i, j, k As Integer
        For i = 0 To 5
            For j = 0 To 5
                k = 0
                While k < 6
                    If i * j * k = 8 Then GoTo found
                    k += 1
                End While
            Next
        Next
        Console.WriteLine("not found")
found:
        Console.WriteLine(i & j & k)
        i = 0
again:
        i += 1
        If i < 5 Then GoTo again
        Console.WriteLine("again " & i)
        GoTo skip
        Console.WriteLine("skipped")
skip:
        Console.WriteLine("end")""",
        "124\nagain 5\nend\n",
    ),
}

CASES["goto_into_if_while_and_select_bodies"] = (
    "",
    """        Dim n As Integer
        n = 6
        GoTo mid
        While n > 0
            Console.WriteLine("top " & n)
mid:
            Console.WriteLine("mid " & n)
            n = n - 4
        End While
        GoTo inside
        If n > 100 Then
            Console.WriteLine("not reached")
        ElseIf n > 50 Then
inside:
            Console.WriteLine("inside " & n)
        Else
            Console.WriteLine("else")
        End If
        If n < 0 Then GoTo case2
        Select Case n
            Case 1
                Console.WriteLine("one")
            Case 2
case2:
                Console.WriteLine("two " & n)
        End Select""",
    "mid 6\ntop 2\nmid 2\ninside -2\ntwo -2\n",
)

CASES["goto_out_of_catch_runs_finally"] = (
    "",
    """        Dim ex As Exception
        Dim i As Integer
        For i = 1 To 3
            Try
                If i = 2 Then Throw New Exception
                Console.WriteLine("ok " & i)
            Catch ex
                Console.WriteLine("failed " & i)
                GoTo done
            Finally
                Console.WriteLine("finally " & i)
            End Try
        Next
done:
        Console.WriteLine("done " & i)""",
    "ok 1\nfinally 1\nfailed 2\nfinally 2\ndone 2\n",
)

CASES["shared_property_and_shared_method"] = (
    """    Class Config
        Private Shared speed_in As Integer = 50
        Public Shared Property Speed As Integer
            Get
                Return speed_in
            End Get
            Set(ByVal value As Integer)
                If value > 100 Then value = 100
                speed_in = value
            End Set
        End Property
        Public Shared Function Twice() As Integer
            Return Speed * 2
        End Function
    End Class""",
    """        Console.WriteLine(Config.Speed)
        Config.Speed = 250
        Console.WriteLine(Config.Speed & " " & Config.Twice())""",
    "50\n100 200\n",
)

CASES["loops_and_exits"] = (
    "",
    CASES["loops_and_exits"][1].replace(
        """        For Each j In New Integer() {}
        Next""", ""),
    "14\n1 2\n",
)


@pytest.mark.parametrize("name", sorted(CASES))
def test_construct(tmp_path: Path, name: str) -> None:
    decls, body, expected = CASES[name]
    assert run_main(tmp_path, body, decls) == expected


def test_divide_by_zero_caught_two_calls_up(tmp_path: Path) -> None:
    decls = """    Function Inner(ByVal d As Double) As Double
        Return 1 / d
    End Function
    Function Middle(ByVal d As Double) As Double
        Return Inner(d) * 2
    End Function"""
    body = """        Dim ex As Exception
        Try
            Console.WriteLine(Middle(0))
        Catch ex
            Console.WriteLine(ex.ErrorCode)
        End Try"""
    assert run_main(tmp_path, body, decls) == "-709\n"


THREADS = """Module Main
    Public my_lock As Integer
    Public shared_count As Integer
    Public done_count As Integer

    Sub Acquire(ByRef sem As Integer)
        While Thread.TestAndSet(sem, 1) <> 0
            Thread.Sleep(1)
        End While
    End Sub

    Public Sub Worker()
        Dim i As Integer
        Dim tmp As Integer
        For i = 1 To 50
            LOCK
            tmp = shared_count
            Thread.Sleep(2)
            shared_count = tmp + 1
            my_lock = 0
        Next
        done_count += 1
    End Sub

    Public Sub Main()
        Dim t1 As New Thread("Worker", 0, "w1")
        Dim t2 As New Thread("Main.Worker", 0, "w2")
        t1.Start()
        t2.Start()
        t1.Join(-1)
        t2.Join(-1)
        Console.WriteLine("count " & shared_count & " done " & done_count & " t=" & Controller.Timer())
    End Sub
End Module
"""


def test_threads_and_test_and_set_on_virtual_clock(tmp_path: Path) -> None:
    locked = run_gpl(tmp_path / "a", THREADS.replace("LOCK", "Acquire(my_lock)"))
    unlocked = run_gpl(tmp_path / "b", THREADS.replace("LOCK", ""))
    assert locked.log == "" and unlocked.log == ""
    assert locked.output.startswith("count 100 done 2")
    # Without the lock the read-sleep-write races lose updates: the lock's ByRef aliasing matters.
    count = int(unlocked.output.split()[1])
    assert count < 100
    # 100 critical sections of 2 ms each, serialised by the lock, on the virtual clock
    assert locked.sim.now() >= 0.2


def test_busy_wait_loop_lets_other_threads_run(tmp_path: Path) -> None:
    """A While loop that polls a module variable without sleeping must not starve the thread that
    sets it: loops get a scheduling checkpoint at their back-edge."""
    src = """Module Main
    Public flag As Boolean
    Public Sub Setter()
        Thread.Sleep(5)
        flag = True
    End Sub
    Public Sub Main()
        Dim t As New Thread("Setter")
        Dim spins As Integer
        t.Start()
        While Not flag
            spins += 1
        End While
        Console.WriteLine("flag seen " & (spins > 0))
    End Sub
End Module
"""
    result = run_gpl(tmp_path, src)
    assert result.log == "" and result.output == "flag seen -1\n"
