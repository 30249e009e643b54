"""Document object proxies, each module owning its objects' execute() (their
recompute). Saved .FCStd files name these classes by module and class: never
rename or move them. The GUI reaches in only through gui_hooks."""
