#!/usr/bin/python3
"""Parses DIR/flat.svg, drape.svg and shear.svg with Python's XML parser and checks them
against DIR/report.json: well-formed SVG with a viewBox, self-contained (no external
references, images or scripts), and one element of class "node" per mapped regular node
(flat.svg, drape.svg: nodes.mapped; shear.svg: nodes.with_angle, the nodes with a thread
angle).

usage: check_svg.py DIR
"""
import json
import os
import sys
import xml.etree.ElementTree as ET

SVG = "{http://www.w3.org/2000/svg}"


def main():
    d = sys.argv[1]
    with open(os.path.join(d, "report.json"), encoding="utf-8") as f:
        report = json.load(f)
    expected = {"flat.svg": report["nodes"]["mapped"], "drape.svg": report["nodes"]["mapped"],
                "shear.svg": report["nodes"]["with_angle"]}
    failures = []
    for name, want in expected.items():
        path = os.path.join(d, name)
        try:
            root = ET.parse(path).getroot()
        except ET.ParseError as e:
            failures.append("%s: not well-formed XML: %s" % (path, e))
            continue
        if root.tag != SVG + "svg" or "viewBox" not in root.attrib:
            failures.append("%s: root is %s, viewBox %s" % (path, root.tag, root.get("viewBox")))
        nodes = 0
        for el in root.iter():
            tag = el.tag.replace(SVG, "")
            if tag in ("image", "script", "foreignObject", "use"):
                failures.append("%s: has a <%s> element" % (path, tag))
            for k, v in el.attrib.items():
                if k.endswith("href") and not v.startswith("#"):
                    failures.append("%s: external reference %s=%s" % (path, k, v))
                if "url(" in v and "url(#" not in v:
                    failures.append("%s: external url in %s" % (path, k))
            if "node" in el.get("class", "").split():
                nodes += 1
        if nodes != want or want <= 0:
            failures.append("%s: %d node marks, report.json says %d" % (path, nodes, want))
        else:
            print("check_svg: %s: ok (%d nodes)" % (path, nodes))
    for f in failures:
        print("check_svg: " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
