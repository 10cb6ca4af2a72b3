"""GPL language semantics for transpiled programs (spec gpl-language.md §4-§11, §14).

One module per concern; generated code imports the functions it needs directly:

* ``conversions`` -- to Integer/Short/Byte (round half away from zero, -710 on overflow),
  Single/Double/Boolean/String, String -> number (-717), CStr rendering, ``convert``, CInt & co.
* ``operators``   -- ``+`` with Strings, ``&``, ``/``, ``\\``, ``Mod``, ``^``, shifts, comparisons,
  And/Or/Xor/Not (-709 division by zero, -710 overflow).
* ``strings``     -- ``StringMembers`` (0-based String members) and legacy functions (1-based).
* ``format``      -- ``Format(value, spec)``.
* ``mathlib``     -- the ``Math`` global class (radians), Fix, Int, Rnd.
* ``arrays``      -- ``GplArray`` (checked, 0-based, upper-bound declarations), ``redim``.
* ``byref``       -- ByRef cells ``Box``, ``AttrRef``, ``ItemRef``.
* ``procedures``  -- ``register_procedure`` / ``find_procedure``.
* ``delegates``   -- ``Delegate``, ``delegate_type``, ``invoke``.
* ``console``     -- the ``Console`` global class and its replaceable sink.
* ``exceptions``  -- ``as_gpl_exception`` for lowered Try/Catch.
* ``constants``   -- ``GPL_CR``, ``GPL_LF``, configuration bits.
* ``catalogue``   -- the tables ``gplrt.builtins`` merges (FUNCTIONS, GLOBAL_CLASSES, ...).
* ``errors``, ``error_codes``, ``gpltypes`` -- GplException, the code table, type vocabulary.
"""
