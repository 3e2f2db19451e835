#!/usr/bin/env python3
"""Fail when a link of the built book or of README.md leads nowhere.

mdBook builds a book whose links point at missing pages or anchors without complaint, so
.ci/run runs this after `mdbook build docs`. Standard library only.

Checked, in every page of docs/book/ (but print.html, which repeats them all) and in README.md:
- a relative link or image must name a file or folder that exists: a page of the book, or a
  file of the repository (docs/src/ and docs/book/ sit at the same depth, so a link that works
  from the Markdown source works from the built page);
- a link with a #fragment into a page of the book must name an id that page has;
- text outside code that still reads `](` or `][` is a Markdown link that did not parse.
Links with a scheme (https:, mailto:) are not fetched: CI has no network.

Usage: python3 docs/check-links.py [REPO_ROOT]   (exit status 1 on a broken link)
"""

import html.parser
import os
import re
import sys
import urllib.parse


class Page(html.parser.HTMLParser):
    """The ids, link targets and stray Markdown of one HTML page."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.ids = set()
        self.links = []  # (target, line)
        self.stray = []  # (text, line)
        self.code_depth = 0

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        for key in ("id", "name"):
            if attrs.get(key):
                self.ids.add(attrs[key])
        target = attrs.get("href") if tag == "a" else attrs.get("src") if tag == "img" else None
        if target is not None:
            self.links.append((target, self.getpos()[0]))
        if tag in ("code", "pre", "script", "style"):
            self.code_depth += 1

    def handle_endtag(self, tag):
        if tag in ("code", "pre", "script", "style") and self.code_depth > 0:
            self.code_depth -= 1

    def handle_data(self, data):
        if self.code_depth == 0 and re.search(r"\]\(|\]\[", data):
            self.stray.append((data.strip()[:80], self.getpos()[0]))


def parse(path):
    page = Page()
    with open(path, encoding="utf-8") as f:
        page.feed(f.read())
    return page


def markdown_links(path):
    """(target, line) of the inline links and images of a Markdown file, code left out."""
    links = []
    in_fence = False
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            if line.lstrip().startswith("```"):
                in_fence = not in_fence
                continue
            if in_fence:
                continue
            line = re.sub(r"`[^`]*`", "", line)
            for match in re.finditer(r"\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)", line):
                links.append((match.group(1), number))
            for match in re.finditer(r"<img[^>]*\ssrc=\"([^\"]+)\"", line):
                links.append((match.group(1), number))
    return links


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else ".")
    book = os.path.join(root, "docs", "book")
    if not os.path.isfile(os.path.join(book, "index.html")):
        print(f"check-links: no built book in {book}: run `mdbook build docs` first")
        return 1

    pages = {}
    for folder, _, files in os.walk(book):
        for name in files:
            if name.endswith(".html") and name != "print.html":
                path = os.path.join(folder, name)
                pages[os.path.normpath(path)] = parse(path)

    sources = [(path, page.links) for path, page in pages.items()]
    sources.append((os.path.join(root, "README.md"), markdown_links(os.path.join(root, "README.md"))))

    errors = []
    for source, links in sources:
        shown = os.path.relpath(source, root)
        for target, line in links:
            parts = urllib.parse.urlsplit(target)
            if parts.scheme or target.startswith("//"):
                continue
            path = urllib.parse.unquote(parts.path)
            resolved = (
                os.path.normpath(os.path.join(os.path.dirname(source), path)) if path else source
            )
            in_book_sources = resolved.startswith(os.path.join(root, "docs", "src") + os.sep)
            if source.endswith(".md") and in_book_sources and path.endswith(".md") and parts.fragment:
                # A README link into the book's sources: the file must exist, and its fragment
                # is judged on the built page, whose ids are mdBook's.
                if not os.path.isfile(resolved):
                    errors.append(f"{shown}:{line}: {target}: {os.path.relpath(resolved, root)} does not exist")
                    continue
                relative = os.path.relpath(resolved, os.path.join(root, "docs", "src"))
                resolved = os.path.normpath(os.path.join(book, relative[: -len(".md")] + ".html"))
            if not os.path.exists(resolved):
                errors.append(f"{shown}:{line}: {target}: {os.path.relpath(resolved, root)} does not exist")
                continue
            if parts.fragment and resolved in pages:
                fragment = urllib.parse.unquote(parts.fragment)
                if fragment not in pages[resolved].ids:
                    errors.append(f"{shown}:{line}: {target}: no id \"{fragment}\" in {os.path.relpath(resolved, root)}")

    for path, page in pages.items():
        for text, line in page.stray:
            errors.append(f"{os.path.relpath(path, root)}:{line}: unparsed Markdown link in \"{text}\"")

    errors = list(dict.fromkeys(errors))  # an image inside a link is reported once
    for error in errors:
        print(error)
    checked = sum(len(links) for _, links in sources)
    print(f"check-links: {checked} links in {len(sources)} files, {len(errors)} broken")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
