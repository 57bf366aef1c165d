#!/usr/bin/python3
"""The README, docs/ and the examples' descriptions link only inside the repository: no web
address, no path leaving it (such as ../shared/docs), and every relative link names a file
that exists. Run by ctest (docs_links_test) with PFEM_SOURCE_DIR=the source tree."""
import glob
import json
import os
import re
import unittest

SOURCE = os.environ["PFEM_SOURCE_DIR"]
# (A loopback address in a sample session is no link out of the repository.)
LEAVING = re.compile(r"https?://(?!127\.0\.0\.1[:/]|localhost[:/])|(?<![\w.])\.\./|shared/docs")
LINK = re.compile(r"\]\(([^)\s]+)\)")


def texts():
    """(name, text, folder relative links start from) of every document checked."""
    for path in [os.path.join(SOURCE, "README.md")] + sorted(glob.glob(os.path.join(SOURCE, "docs", "*.md"))):
        with open(path, encoding="utf-8") as f:
            yield os.path.relpath(path, SOURCE), f.read(), os.path.dirname(path)
    for path in sorted(glob.glob(os.path.join(SOURCE, "examples", "**", "*.json"), recursive=True)):
        with open(path, encoding="utf-8") as f:
            yield os.path.relpath(path, SOURCE), json.load(f).get("description", ""), SOURCE


class DocsLinksTest(unittest.TestCase):
    def test_nothing_leaves_the_repository(self):
        for name, text, _ in texts():
            for number, line in enumerate(text.splitlines(), 1):
                self.assertIsNone(LEAVING.search(line), f"{name}:{number}: {line.strip()}")

    def test_relative_links_exist(self):
        checked = 0
        for name, text, base in texts():
            for target in LINK.findall(text):
                path = os.path.normpath(os.path.join(base, target.split("#")[0]))
                self.assertTrue(path.startswith(SOURCE + os.sep), f"{name}: {target} leaves the repository")
                self.assertTrue(os.path.exists(path), f"{name}: {target} does not exist")
                checked += 1
        self.assertGreaterEqual(checked, 4)  # the README's links into docs/

    def test_the_checker_catches_a_link_out(self):
        for bad in ("see ../shared/docs/theory.md", "[x](https://example.org)", "`../reference/paper.txt`"):
            self.assertIsNotNone(LEAVING.search(bad), bad)


if __name__ == "__main__":
    unittest.main()
