"""TMscript syntax: tokens, the tree, the parser (spec §1-§2)."""
