"""The transpiler's catalogue reads Location, RefFrame and Profile as CATALOGUE.md intends."""

from __future__ import annotations

import types

from gpl2py.gpl.semantics import types as t
from gpl2py.gpl.semantics.catalogue_gen import build_catalogue
from gplrt.geometry import Location, RefFrame
from gplrt.motion.profile import Profile


def _catalogue():  # type: ignore[no-untyped-def]
    mod = types.ModuleType("geometry_builtins")
    mod.Location, mod.RefFrame, mod.Profile = Location, RefFrame, Profile
    mod.CLASSES = {"Location": "Location", "RefFrame": "RefFrame", "Profile": "Profile"}
    mod.GLOBAL_CLASSES, mod.FUNCTIONS, mod.CONSTANTS, mod.TYPE_MEMBERS = {}, {}, {}, {}
    return build_catalogue(mod)


def test_location_members() -> None:
    loc = _catalogue().lookup_class("location")
    assert loc is not None and not loc.is_global
    assert not loc.constructor
    for name in ("X", "Y", "Z", "Yaw", "Pitch", "Roll", "ZClearance"):
        m = loc.member(name)
        assert m is not None and m.kind == "property" and m.settable and m.result is t.DOUBLE, name
    for name in ("Type", "Config"):
        m = loc.member(name)
        assert m is not None and m.settable and m.result is t.INTEGER
    ref = loc.member("RefFrame")
    assert ref is not None and ref.settable and ref.result == t.ClassType.of("RefFrame", builtin=True)
    angle = loc.member("Angle")
    assert angle is not None and angle.kind == "method" and angle.settable
    xyz = loc.member("XYZ")
    assert xyz is not None and (xyz.min_args, xyz.max_args) == (0, 6) and xyz.result is t.VOID
    assert loc.member("Angles").max_args == 12  # type: ignore[union-attr]
    for shared in ("Distance", "XYZValue"):
        assert loc.member(shared).shared  # type: ignore[union-attr]
    for name in ("Mul", "Inverse", "Clone", "KineSol", "Pos", "PosWrtRef"):
        assert loc.member(name).result == t.ClassType.of("Location", builtin=True), name  # type: ignore[union-attr]
    assert loc.member("from_pose") is None and loc.member("set_Angle") is None


def test_refframe_and_profile_members() -> None:
    cat = _catalogue()
    rf = cat.lookup_class("RefFrame")
    assert rf is not None
    assert rf.member("Pos").kind == "method"  # type: ignore[union-attr]
    for name in ("PalletIndex", "PalletMaxIndex", "PalletPitch"):
        m = rf.member(name)
        assert m is not None and m.kind == "method" and m.settable, name
    assert rf.member("PalletOrder").settable and rf.member("Loc").settable  # type: ignore[union-attr]
    assert rf.member("Clone") is None  # not a documented RefFrame member
    prof = cat.lookup_class("Profile")
    assert prof is not None
    for name in ("Speed", "Speed2", "Accel", "Decel", "AccelRamp", "DecelRamp", "InRange"):
        m = prof.member(name)
        assert m is not None and m.settable and m.result is t.DOUBLE, name
    assert prof.member("Straight").result is t.BOOLEAN  # type: ignore[union-attr]
