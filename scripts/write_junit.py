#!/usr/bin/env python3
"""Writes one JUnit testsuite for scripts/test_summary.py from run records of the hardening scripts
(run_sanitizers.sh, run_fuzz.sh): each record "name|seconds|verdict|log" is one testcase, failed
unless verdict is "passed", with the tail of its log as the failure text.
usage: write_junit.py SUITE OUT.xml RECORD...
"""
import pathlib
import re
import sys
import xml.etree.ElementTree as ET

# rosconsole colours its lines (ESC [ ... m); XML 1.0 allows no control characters but tab, LF and
# CR, and ElementTree writes them as they are: one ESC made the whole file unreadable.
_ANSI = re.compile(r"\x1b\[[0-9;]*[A-Za-z]")
_NOT_XML = re.compile(r"[\x00-\x08\x0b\x0c\x0e-\x1f]")


def xml_text(text):
    return _NOT_XML.sub("?", _ANSI.sub("", text))


def main(suite_name, out, records):
    suite = ET.Element("testsuite", name=suite_name)
    for record in records:
        name, seconds, verdict, log = record.split("|", 3)
        case = ET.SubElement(suite, "testcase", classname=suite_name, name=name, time=seconds)
        if verdict != "passed":
            path = pathlib.Path(log) if log else None
            tail = path.read_text(errors="replace")[-4000:] if path and path.is_file() else ""
            failure = ET.SubElement(case, "failure", message=xml_text(f"{verdict} (log: {log})"))
            failure.text = xml_text(tail)
    pathlib.Path(out).parent.mkdir(parents=True, exist_ok=True)
    ET.ElementTree(suite).write(out)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], sys.argv[3:])
