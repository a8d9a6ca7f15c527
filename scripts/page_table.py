#!/usr/bin/env python3
"""Puts a script's table into a README between its markers: "<!-- NAME begin -->" and
"<!-- NAME end -->". A page without them gets them at its end under HEADING. The table scripts
(building-table.sh, cascade-cost-table.sh) write their measured tables through this, never by hand.
The page is replaced whole (written beside it, then renamed), never left half-written.

Usage: page_table.py PAGE NAME HEADING TABLE_FILE
"""
import os
import sys


def main() -> int:
    if len(sys.argv) != 5 or sys.argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return 0 if len(sys.argv) == 2 else 2
    page, name, heading, table_file = sys.argv[1:]
    try:
        table = open(table_file).read()
        text = open(page).read()
    except OSError as e:
        print(f"page_table: {e.filename}: {e.strerror}", file=sys.stderr)
        return 1
    begin, end = f"<!-- {name} begin -->\n", f"<!-- {name} end -->"
    if begin not in text:
        text += f"\n## {heading}\n\n{begin}{end}\n"
    head, rest = text.split(begin)
    if end not in rest:
        print(f"page_table: {page}: '{begin.strip()}' has no '{end}' after it", file=sys.stderr)
        return 1
    tmp = page + ".tmp"
    with open(tmp, "w") as out:
        out.write(head + begin + table + end + rest.split(end, 1)[1])
    os.replace(tmp, page)
    return 0


if __name__ == "__main__":
    sys.exit(main())
