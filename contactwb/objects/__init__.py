"""Document object proxies. Saved .FCStd files name these classes by module
and class: never rename or move them."""
