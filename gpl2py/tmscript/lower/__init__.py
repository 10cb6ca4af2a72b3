"""TMscript -> Python on ``gplrt.tm`` (docs/design/tmscript.md)."""
