#!/usr/bin/env python3
"""Checks docs/farms/sylva-openjd.yaml against a `sylva jobs --json` listing.

No OpenJD validator is packaged for Debian 12 (openjd-model is on PyPI only), so this
reads the template with PyYAML and checks what the recipe relies on: the 2023-09
specification, the Render step's INT task parameter ChunkStart with the range
'0-{{Param.LastJob}}:{{Param.ChunkSize}}', a script that renders --jobs START-END with
END = START + ChunkSize - 1, and an Assemble step depending on Render. Then it expands
the chunks for LastJob = total - 1 and several chunk sizes, clamps each chunk's end to
the last job as `sylva render --jobs` does, and checks that every job index is covered
exactly once.

usage: check_openjd_chunks.py TEMPLATE JOBS_JSON
"""
import json
import re
import sys

import yaml


def expand_range(text):
    """An OpenJD INT range expression 'a-b:s' (or 'a-b', or 'a') into its values."""
    match = re.fullmatch(r"\s*(-?\d+)\s*(?:-\s*(-?\d+)\s*(?::\s*(\d+))?)?\s*", text)
    if not match:
        raise ValueError(f"not a range expression: {text!r}")
    first = int(match.group(1))
    last = int(match.group(2)) if match.group(2) else first
    step = int(match.group(3)) if match.group(3) else 1
    return list(range(first, last + 1, step))


def main():
    template = yaml.safe_load(open(sys.argv[1]))
    total = json.load(open(sys.argv[2]))["total"]
    problems = []
    if template.get("specificationVersion") != "jobtemplate-2023-09":
        problems.append("specificationVersion is not jobtemplate-2023-09")
    parameters = {p["name"]: p for p in template["parameterDefinitions"]}
    for name in ("Project", "OutputFolder", "DiskCache", "LastJob", "ChunkSize"):
        if name not in parameters:
            problems.append(f"job parameter {name} missing")
    steps = {s["name"]: s for s in template["steps"]}
    render = steps.get("Render")
    assemble = steps.get("Assemble")
    if render is None or assemble is None:
        problems.append("steps Render and Assemble are required")
        print("\n".join(problems))
        return 1
    if {"dependsOn": "Render"} not in assemble.get("dependencies", []):
        problems.append("Assemble does not depend on Render")
    (chunk,) = render["parameterSpace"]["taskParameterDefinitions"]
    if chunk["name"] != "ChunkStart" or chunk["type"] != "INT":
        problems.append("the Render task parameter must be INT ChunkStart")
    script = render["script"]["embeddedFiles"][0]["data"]
    if "end=$((start + {{Param.ChunkSize}} - 1))" not in script or '--jobs "$start-$end"' not in script:
        problems.append("the Render script does not render --jobs START-(START+ChunkSize-1)")
    if "{{Task.Param.ChunkStart}}" not in script:
        problems.append("the Render script does not read Task.Param.ChunkStart")
    last = total - 1
    for size in (1, 3, parameters["ChunkSize"].get("default", 8), total, total + 5):
        text = chunk["range"].replace("{{Param.LastJob}}", str(last)).replace(
            "{{Param.ChunkSize}}", str(size))
        covered = []
        for start in expand_range(text):
            end = min(start + size - 1, last)  # sylva render clamps a range at the last job
            covered.extend(range(start, end + 1))
        if sorted(covered) != list(range(total)):
            problems.append(f"chunk size {size}: jobs not covered exactly once")
        else:
            print(f"chunk size {size}: {len(expand_range(text))} tasks cover jobs 0-{last} once")
    if problems:
        print("\n".join(problems), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
