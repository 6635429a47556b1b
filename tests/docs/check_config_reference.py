#!/usr/bin/env python3
"""Fails when a config key the code accepts is missing from its reference doc, or the doc lists a key the code
does not accept.

Every TOML table the configs read is checked by one `only({...})` call that lists the keys it accepts (unknown
keys are errors). The reference docs have one section per such call: a `## ` heading, then a table whose first
column holds the keys in backticks. Each code list must equal one documented section's keys exactly, and each
documented section must equal one code list, so a key added, renamed or removed on either side fails here with
the file and line of the code list and the nearest section.

Usage: check_config_reference.py SOURCE_DIR
"""
import re
import sys
from pathlib import Path

# Which code reads which config, and the reference that documents it.
REFERENCES = {
    "docs/SCENE-CONFIG.md": ["compiler/scene/scene_config.cpp"],
    "docs/KIOSK-CONFIG.md": ["firmware-host/kiosk_config.cpp", "firmware-host/device_config.cpp"],
}
ONLY_CALL = re.compile(r"\bonly\(\s*\{([^}]*)\}\s*\)", re.S)
STRING_LITERAL = re.compile(r'"([^"\\]*)"')
KEY_ROW = re.compile(r"^\|\s*`([^`]+)`\s*\|")


def code_lists(source_dir, files):
    """(file:line, frozenset of keys) for every only({...}) call."""
    out = []
    for name in files:
        text = (source_dir / name).read_text()
        for m in ONLY_CALL.finditer(text):
            line = text.count("\n", 0, m.start()) + 1
            out.append((f"{name}:{line}", frozenset(STRING_LITERAL.findall(m.group(1)))))
    return out


def doc_sections(path):
    """(heading, frozenset of keys) for every section whose table lists keys."""
    sections, heading, keys = [], None, set()
    for line in path.read_text().splitlines():
        if line.startswith("#"):
            if heading and keys:
                sections.append((heading, frozenset(keys)))
            heading, keys = line.lstrip("#").strip(), set()
        elif (m := KEY_ROW.match(line)) and heading:
            keys.add(m.group(1))
    if heading and keys:
        sections.append((heading, frozenset(keys)))
    return sections


def nearest(keys, candidates):
    """The candidate sharing most keys, or None when none shares any (a new table)."""
    best = max(candidates, key=lambda c: len(keys & c[1]) - len(keys ^ c[1])) if candidates else None
    return best if best is not None and keys & best[1] else None


def unmatched(items, others, describe):
    """A problem for each (name, keys) of items whose key set no entry of others has exactly."""
    other_sets = {keys for _, keys in others}
    return [describe(name, keys, nearest(keys, others)) for name, keys in items if keys not in other_sets]


def check(source_dir, doc, files):
    path = source_dir / doc
    if not path.exists():
        return [f"{doc}: missing (it must document every key of {', '.join(files)})"]
    lists, sections = code_lists(source_dir, files), doc_sections(path)
    if not lists:
        return [f"{', '.join(files)}: no only({{...}}) key lists found; has the config reader changed shape?"]

    def undocumented(where, keys, section):
        heading, documented = section or ("(none: no section documents any of these keys; add one)", frozenset())
        return (f"{where}: keys accepted but not documented in {doc} section '{heading}': "
                f"{sorted(keys - documented) or '-'}; documented there but not accepted: "
                f"{sorted(documented - keys) or '-'}")

    def unaccepted(heading, keys, code_list):
        where, accepted = code_list or ("(none: no code list accepts any of these keys)", frozenset())
        return (f"{doc} section '{heading}': keys documented but not accepted by the code list at {where}: "
                f"{sorted(keys - accepted) or '-'}; accepted there but not documented: "
                f"{sorted(accepted - keys) or '-'}")

    problems = unmatched(lists, sections, undocumented) + unmatched(sections, lists, unaccepted)
    if not problems:
        total = sum(len(k) for _, k in lists)
        print(f"ok   {doc}: {len(lists)} tables, {total} keys, each documented")
    return problems


def main():
    source_dir = Path(sys.argv[1])
    problems = [p for doc, files in REFERENCES.items() for p in check(source_dir, doc, files)]
    for p in problems:
        print("FAIL " + p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
