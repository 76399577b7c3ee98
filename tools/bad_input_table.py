# SPDX-License-Identifier: LGPL-2.1-or-later
"""Print the rows table of docs/bad-input.md from the catalogue's real messages.

Runs every row of tests/python/bad_input_cases.py through ``python3 -m facet`` in a
temporary folder and prints one Markdown row each (row, command, exit status, message).
Paste the output under "## Rows" after changing the catalogue or a message:

    /usr/bin/python3 tools/bad_input_table.py
"""

import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests", "python"))

import bad_input_cases as cases  # noqa: E402


def main():
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "workbench"))
    with tempfile.TemporaryDirectory(prefix="facet-bad-table-") as tmp:
        for row in cases.ROWS:
            folder = os.path.join(tmp, row.name)
            row.write(folder)
            done = subprocess.run([sys.executable, "-m", "facet", *row.command(folder)],
                                  capture_output=True, text=True, env=env)
            err = done.stderr.strip().replace(folder + os.sep, "")
            command = " ".join(a.replace(folder + os.sep, "") for a in row.command(folder))
            if row.works:
                warnings = "; ".join(line.replace("facet: warning: ", "")
                                     for line in err.splitlines())
                message = "works" + (f" (warning: {warnings})" if warnings else "")
            else:
                message = "`" + err.replace("|", "\\|") + "`"
            print(f"| `{row.name}` | `facet {command}` | {done.returncode} | {message} |")


if __name__ == "__main__":
    main()
