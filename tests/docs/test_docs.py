"""The user documentation checked against the repository and the built command (CTest `docs`):
README.md's length, its two set-up commands and pictures, links that resolve, no issue numbers,
and every `reftrack COMMAND --option` the guides show offered by that command's --help."""

import os
import pathlib
import re
import subprocess
import unittest

ROOT = pathlib.Path(os.environ.get("REFTRACK_SOURCE_DIR", pathlib.Path(__file__).parents[2]))
REFTRACK = os.environ.get("REFTRACK_BINARY", str(ROOT / "build" / "app" / "reftrack"))
README = ROOT / "README.md"
GUIDES = [README, ROOT / "engine/README.md", ROOT / "app/README.md",
          ROOT / "app/research/README.md", ROOT / "app/python/README.md"]
TWO_COMMANDS = (
    "```sh\n"
    "bash scripts/demo.sh    # install what is needed, build (Release), run the demo on the embedded scene\n"
    "bash scripts/test.sh    # install what is needed, build, run the whole test suite (CTest)\n"
    "```\n")
MAX_README_LINES = 350
MAX_PICTURE_BYTES = 600 * 1024


def links(path):
    """(target, line) of every Markdown link and image in a file, code blocks left out."""
    text = re.sub(r"```.*?```", lambda m: "\n" * m.group(0).count("\n"), path.read_text(), flags=re.S)
    for m in re.finditer(r"!?\[[^\]]*\]\(([^)\s]+)\)", text):
        yield m.group(1), text.count("\n", 0, m.start()) + 1


def anchors(path):
    """The anchors GitHub gives a Markdown file's headings (lower case, punctuation dropped)."""
    text = re.sub(r"```.*?```", "", path.read_text(), flags=re.S)
    return {re.sub(r"[^\w\- ]", "", h.strip().lower()).replace(" ", "-")
            for h in re.findall(r"^#+ (.*)$", text, flags=re.M)}


def shown_commands(path):
    """Every `reftrack SUBCOMMAND ...` line of the file's shell blocks and inline code."""
    text = path.read_text()
    pieces = []
    for block in re.findall(r"```sh\n(.*?)```", text, flags=re.S):
        pieces += block.replace("\\\n", " ").splitlines()
    prose = re.sub(r"```.*?```", "", text, flags=re.S)
    pieces += [span.replace("\n", " ") for span in re.findall(r"`([^`]+)`", prose)]
    for piece in pieces:
        for m in re.finditer(r"(?:^|[\s(])reftrack ([a-z][a-z0-9-]*)((?: [^#|;]*)?)", piece):
            yield m.group(1), m.group(2)


class Docs(unittest.TestCase):
    def test_readme_is_short_and_keeps_the_two_commands(self):
        text = README.read_text()
        self.assertLessEqual(len(text.splitlines()), MAX_README_LINES)
        self.assertEqual(text.count(TWO_COMMANDS), 1, "README.md's two set-up commands changed")
        self.assertIn("scripts/test.sh", (ROOT / ".ci/run").read_text())

    def test_pictures_exist_and_are_small(self):
        pictures = [t for t, _ in links(README) if re.search(r"\.(png|jpe?g)$", t)]
        self.assertGreaterEqual(len(pictures), 2)
        for target in pictures:
            path = README.parent / target
            self.assertTrue(path.is_file(), target)
            self.assertLessEqual(path.stat().st_size, MAX_PICTURE_BYTES, target)

    def test_relative_links_resolve(self):
        for guide in GUIDES:
            for target, line in links(guide):
                if re.match(r"[a-z]+:", target):
                    continue
                file, _, anchor = target.partition("#")
                path = (guide.parent / file).resolve() if file else guide
                self.assertTrue(path.exists(), f"{guide.relative_to(ROOT)}:{line}: {target}")
                if anchor:
                    self.assertIn(anchor, anchors(path), f"{guide.relative_to(ROOT)}:{line}: {target}")

    def test_no_issue_numbers_in_user_docs(self):
        for guide in GUIDES:
            for n, line in enumerate(guide.read_text().splitlines(), 1):
                self.assertIsNone(re.search(r"\bissues? ?#?[0-9]+|(?<!--)\bstep [0-9]+\b", line, re.I),
                                  f"{guide.relative_to(ROOT)}:{n}: {line}")

    def test_every_option_shown_is_offered(self):
        helps = {}
        missing = []
        for guide in GUIDES:
            for command, rest in shown_commands(guide):
                if command not in helps:
                    run = subprocess.run([REFTRACK, command, "--help"], capture_output=True,
                                         text=True)
                    helps[command] = run.stdout if run.returncode == 0 else None
                if helps[command] is None:
                    missing.append(f"{guide.relative_to(ROOT)}: reftrack {command}: no such command")
                    continue
                for option in re.findall(r"(?<![\w-])(--[a-z][a-z0-9-]*)", rest):
                    if not re.search(re.escape(option) + r"(?![\w-])", helps[command]):
                        missing.append(f"{guide.relative_to(ROOT)}: reftrack {command} {option}")
        self.assertEqual(sorted(set(missing)), [])


if __name__ == "__main__":
    unittest.main(verbosity=2)
