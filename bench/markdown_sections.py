"""Each benchmark script owns one marked section of docs/benchmarks.md."""
import os


def write_section(path, name, text):
    """Replaces the section between `<!-- NAME: begin -->` and `<!-- NAME: end -->`
    of the Markdown file (appends it if absent), keeping the rest."""
    begin, end = f"<!-- {name}: begin -->", f"<!-- {name}: end -->"
    old = open(path).read() if os.path.isfile(path) else "# Benchmarks\n"
    section = f"{begin}\n{text}\n{end}"
    if begin in old and end in old:
        new = old[:old.index(begin)] + section + old[old.index(end) + len(end):]
    else:
        new = old.rstrip("\n") + "\n\n" + section + "\n"
    with open(path, "w") as stream:
        stream.write(new)
