"""/work/shared/corpus/vplus/swri-ros/ros.v2 lowered by hand onto gplrt.vplus, statement by
statement, the way docs/design/vplus-runtime.md tells the front end to lower it: every variable a
cell (GLOBAL ``vp.G``, AUTO ``vp.Cell``/``vp.VArray``), every argument a reference (a variable's
cell, ``vp.byval`` for an expression, the array itself for ``jts[]``), FOR as a counted loop over a
cell, GOTO 99/100 as the structured exits they are.  The V+ line each statement comes from is in
the comment at its right.

The one change from the file: a.ros takes the two port numbers as arguments (the file hard-codes
11000 and 11002), so that tests on a shared machine use free ports.  Until the front end lands,
this is how the runtime is shown to serve ros.v2.
"""

from __future__ import annotations

from gplrt import vplus as vp

G = vp.G


@vp.program("a.ros")
def a_ros(cmd_port: int = 11000, fdb_port: int = 11002) -> None:
    G["cmd.port"].v = cmd_port                       # cmd.port = 11000
    G["fdb.port"].v = fdb_port                       # fdb.port = 11002
    G["delay.cmd"].v = vp.div(1, 10)                 # delay.cmd = 1/10
    G["delay.fdb"].v = vp.div(1, 10)                 # delay.fdb = 1/10
    G["run"].v = vp.TRUE                             # run = TRUE
    vp.execute(5, ros_srv_cmd)                       # EXECUTE 5 ros.srv.cmd()
    vp.execute(6, ros_srv_fdb)                       # EXECUTE 6 ros.srv.fdb()
    return                                           # RETURN


@vp.program("ros.msg.create")
def ros_msg_create(msg_len: vp.Ref, msg_type: vp.Ref, cmd_type: vp.Ref, msg_reply: vp.Ref,
                   msg_unused: vp.Ref, msg: vp.Ref) -> None:
    s_msg_len, s_msg_type, s_cmd_type = vp.Cell("$msg.len"), vp.Cell("$msg.type"), vp.Cell("$cmd.type")
    s_msg_reply, s_msg_unused = vp.Cell("$msg.reply"), vp.Cell("$msg.unused")
    s_msg_len.v = vp.s_lngb(msg_len.v)               # $msg.len = $LNGB(msg.len)
    s_msg_type.v = vp.s_lngb(msg_type.v)
    s_cmd_type.v = vp.s_lngb(cmd_type.v)
    s_msg_reply.v = vp.s_lngb(msg_reply.v)
    s_msg_unused.v = vp.s_lngb(msg_unused.v)
    ros_rev_bytes(s_msg_len, G["$msg.len.rev"])      # CALL ros.rev.bytes($msg.len, $msg.len.rev)
    ros_rev_bytes(s_msg_type, G["$msg.type.rev"])
    ros_rev_bytes(s_cmd_type, G["$cmd.type.rev"])
    ros_rev_bytes(s_msg_reply, G["$msg.reply.rev"])
    ros_rev_bytes(s_msg_unused, G["$msg.unused.rev"])
    msg.v = ""                                       # $msg = ""
    msg.v = vp.s_encode(G["$msg.len.rev"].v, G["$msg.type.rev"].v, G["$cmd.type.rev"].v,
                        G["$msg.reply.rev"].v, G["$msg.unused.rev"].v)
    return


@vp.program("ros.read.4bytes")
def ros_read_4bytes(lun: vp.Ref, long: vp.Ref) -> None:
    tmp, i, c = vp.Cell("$tmp"), vp.Cell("i"), vp.VArray("c", 4)
    tmp.v = ""                                       # $tmp = ""
    i.v = 1                                          # FOR i = 1 TO 4
    while vp.truth(vp.le(i.v, 4)):
        c[i.v] = vp.getc(lun.v, 2)                   # c[i] = GETC(lun,2)
        tmp.v = vp.add(tmp.v, vp.s_chr(c[i.v]))      # $tmp = $tmp+$CHR(c[i])
        i.v = i.v + 1
    ros_rev_bytes(tmp, G["$msg"])                    # CALL ros.rev.bytes($tmp, $msg)
    long.v = vp.lngb(G["$msg"].v)                    # long = LNGB($msg)


@vp.program("ros.read.joints")
def ros_read_joints(lun: vp.Ref, jts: vp.VArray) -> None:
    c, idx, tmp, msg_jts = vp.VArray("c", 4), vp.Cell("idx"), vp.Cell("$tmp"), vp.VArray("$msg.jts", 10)
    i = G["i"]                                       # (i is not declared: GLOBAL)
    idx.v = 1                                        # FOR idx = 1 TO 10
    while vp.truth(vp.le(idx.v, 10)):
        tmp.v = ""
        i.v = 1                                      # FOR i = 1 TO 4
        while vp.truth(vp.le(i.v, 4)):
            c[i.v] = vp.getc(lun.v, 2)
            tmp.v = vp.add(tmp.v, vp.s_chr(c[i.v]))
            i.v = i.v + 1
        ros_rev_bytes(tmp, msg_jts.ref(idx.v))       # CALL ros.rev.bytes($tmp, $msg.jts[idx])
        jts[idx.v] = vp.fltb(msg_jts[idx.v])         # jts[idx] = FLTB($msg.jts[idx])
        jts[idx.v] = vp.div(vp.mul(jts[idx.v], 180), vp.PI)
        idx.v = idx.v + 1


@vp.program("ros.rev.bytes")
def ros_rev_bytes(in_: vp.Ref, out: vp.Ref) -> None:
    str_len, i, chr_ = vp.Cell("str.len"), vp.Cell("i"), vp.Cell("$chr")
    str_len.v = vp.len_(in_.v)                       # str.len = LEN($in)
    chr_.v = ""
    out.v = ""
    i.v = str_len.v                                  # FOR i = str.len TO 1 STEP -1
    while vp.truth(vp.ge(i.v, 1)):
        chr_.v = vp.s_mid(in_.v, i.v, 1)             # $chr = $MID($in,i,1)
        out.v = vp.add(out.v, chr_.v)                # $out = $out+$chr
        i.v = i.v - 1
    return


@vp.program("ros.srv.cmd")
def ros_srv_cmd() -> None:
    lun, status, idx = vp.Cell("lun"), vp.Cell("status"), vp.Cell("idx")
    msg_len, msg_type, cmd_type = vp.Cell("msg.len"), vp.Cell("msg.type"), vp.Cell("cmd.type")
    msg_reply, msg_unused = vp.Cell("msg.reply"), vp.Cell("msg.unused")
    msg_jts, tmp_str = vp.VArray("$msg.jts", 10), vp.Cell("$tmp.str")
    jts = vp.VArray("jts", 10)                       # AUTO REAL jts[10]
    msg = vp.Cell("$msg")
    msg_len.v = 0
    msg_type.v = 0
    cmd_type.v = 0
    msg_reply.v = 0
    idx.v = 1                                        # FOR idx = 1 TO 10: jts[idx] = 0
    while vp.truth(vp.le(idx.v, 10)):
        jts[idx.v] = 0
        idx.v = idx.v + 1
    vp.attach(lun, 4, "TCP")                         # ATTACH (lun, 4) "TCP"
    vp.fopen(lun, vp.add(vp.add("/LOCAL_PORT", vp.s_encode(G["cmd.port"].v)),
                         " /CLIENTS 1 /BUFFER_SIZE 1024"), 16)
    status.v = vp.iostat(lun.v)
    if vp.truth(vp.lt(status.v, 0)):
        vp.type_(vp.add("Error opening cmd TCP port: ", vp.s_error(status.v)))
        return                                       # GOTO 100
    ros_read_4bytes(lun, msg_unused)                 # CALL ros.read.4bytes(lun, msg.unused)
    vp.type_("ROS connected to V+ command server")
    vp.select_robot(1)                               # SELECT ROBOT = 1
    vp.attach(0)                                     # ATTACH ()
    vp.speed(100, always=True)                       # SPEED 100 ALWAYS
    vp.accel(100, 100)                               # ACCEL (1) 100, 100
    while vp.truth(G["run"].v):                      # WHILE run DO
        ros_read_4bytes(lun, msg_len)
        ros_read_4bytes(lun, msg_type)
        ros_read_4bytes(lun, cmd_type)
        ros_read_4bytes(lun, msg_reply)
        ros_read_4bytes(lun, msg_unused)
        ros_read_joints(lun, jts)                    # CALL ros.read.joints(lun, jts[])
        if vp.truth(vp.eq(msg_unused.v, -2)):        # IF (msg.unused == -2) THEN GOTO 99
            break
        ros_msg_create(vp.byval(56), vp.byval(10), vp.byval(3), vp.byval(1), vp.byval(0), msg)
        G["#loc"].v = vp.p_ppoint(jts[1], jts[2], jts[3], jts[4], jts[5], jts[6])
        idx.v = 1
        while vp.truth(vp.le(idx.v, 10)):
            jts[idx.v] = 0
            msg.v = vp.add(msg.v, msg_jts[idx.v])    # $msg = $msg+$msg.jts[idx]
            idx.v = idx.v + 1
        vp.write(lun.v, msg.v, vp.fmt("/S"))         # WRITE (lun) $msg, /S
        vp.move(G["#loc"].v)                         # MOVE #loc
    vp.fclose(lun.v)                                 # 99 FCLOSE (lun)
    vp.detach(lun.v)
    ros_stop()                                       # CALL ros.stop()
    return                                           # 100 RETURN


@vp.program("ros.srv.fdb")
def ros_srv_fdb() -> None:
    idx, lun, status = vp.Cell("idx"), vp.Cell("lun"), vp.Cell("status")
    jts = vp.VArray("jts", 10)
    tmp_str, msg_jts = vp.Cell("$tmp.str"), vp.VArray("$msg.jts", 10)
    cur_loc = vp.Cell("#cur.loc")                    # AUTO LOC #cur.loc
    msg = vp.Cell("$msg")
    tmp_str.v = ""
    idx.v = 1
    while vp.truth(vp.le(idx.v, 10)):
        jts[idx.v] = 0
        idx.v = idx.v + 1
    vp.attach(lun, 4, "TCP")
    vp.fopen(lun, vp.add(vp.add("/LOCAL_PORT", vp.s_encode(G["fdb.port"].v)),
                         " /CLIENTS 1 /BUFFER_SIZE 1024"), 16)
    status.v = vp.iostat(lun.v)
    if vp.truth(vp.lt(status.v, 0)):
        vp.type_(vp.add("Error opening fdb TCP port: ", vp.s_error(status.v)))
        return
    while vp.truth(G["run"].v):
        ros_msg_create(vp.byval(56), vp.byval(10), vp.byval(1), vp.byval(0), vp.byval(0), msg)
        vp.here_into(cur_loc)                        # HERE #cur.loc
        vp.decompose(jts, 1, cur_loc.v)              # DECOMPOSE jts[1] = #cur.loc
        idx.v = 1
        while vp.truth(vp.le(idx.v, 10)):
            jts[idx.v] = vp.div(vp.mul(jts[idx.v], vp.PI), 180)
            tmp_str.v = vp.s_fltb(jts[idx.v])
            ros_rev_bytes(tmp_str, msg_jts.ref(idx.v))
            msg.v = vp.add(msg.v, msg_jts[idx.v])
            idx.v = idx.v + 1
        vp.write(lun.v, msg.v, vp.fmt("/S"))         # WRITE (lun) $msg, /S
        vp.wait_event(None, G["delay.fdb"].v)        # WAIT.EVENT , delay.fdb
    vp.fclose(lun.v)
    vp.detach(lun.v)
    return


@vp.program("ros.stop")
def ros_stop() -> None:
    G["run"].v = vp.FALSE                            # run = FALSE
