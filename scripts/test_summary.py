#!/usr/bin/env python3
"""Counts test cases in the JUnit XML under a results folder and prints 'N passed, N failed'.

catkin_make run_tests exits 0 on failure and catkin_test_results double-counts gtest >= 1.10 XML,
so the verdict is ours: non-zero exit on any failure, or when no test ran at all.
"""
import pathlib
import sys
import xml.etree.ElementTree as ET


def main(folder):
    passed, failed, skipped = 0, [], 0
    files = sorted(pathlib.Path(folder).rglob("*.xml"))
    for f in files:
        try:
            root = ET.parse(f).getroot()
        except ET.ParseError as e:
            failed.append(f"{f.name}: unreadable result ({e})")
            continue
        for case in root.iter("testcase"):
            name = f"{case.get('classname', '')}.{case.get('name', '')}"
            if case.find("failure") is not None or case.find("error") is not None:
                failed.append(name)
            elif case.find("skipped") is not None or case.get("status") == "notrun":
                skipped += 1
            else:
                passed += 1
    for name in failed:
        print(f"FAILED: {name}")
    if passed + len(failed) == 0:
        print(f"no test results under {folder}")
    tail = f", {skipped} skipped" if skipped else ""
    print(f"{passed} passed, {len(failed)} failed{tail}")
    return 1 if failed or passed == 0 else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "build/test_results"))
