"""junit_cases.py A.xml B.xml: exit 0 when both JUnit files hold the same testcases in the
same order (name, classname, failure or error with message and text) and the same
system-out; times, timestamps and hosts are ignored."""
import sys
import xml.etree.ElementTree as ET


def cases(path):
    suite = ET.parse(path).getroot().find("testsuite")
    out = []
    for case in suite.iter("testcase"):
        outcome = [(c.tag, c.get("message"), c.get("type"), c.text) for c in case]
        out.append((case.get("name"), case.get("classname"), outcome))
    counts = {k: suite.get(k) for k in ("tests", "failures", "errors")}
    return out, counts, suite.findtext("system-out"), suite.findtext("system-err")


a, b = cases(sys.argv[1]), cases(sys.argv[2])
for what, x, y in zip(("testcases", "counts", "system-out", "system-err"), a, b):
    if x != y:
        print(f"{what} differ: {sys.argv[1]} / {sys.argv[2]}")
        if isinstance(x, list):
            diff = [(i, p, q) for i, (p, q) in enumerate(zip(x, y)) if p != q][:3]
            print(len(x), len(y), diff)
        sys.exit(1)
