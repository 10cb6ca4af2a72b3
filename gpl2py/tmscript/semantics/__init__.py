"""TMscript semantics: names, scopes, the built-in catalogue, the checks the manual states."""
