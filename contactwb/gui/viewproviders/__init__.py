"""View providers, one module per class (saved files name them: the classes
keep their names; the modules they were in before stay importable)."""
