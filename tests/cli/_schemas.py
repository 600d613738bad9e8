"""Structural validators for the JUnit XML and SARIF 2.1.0 that `cpn-verify check` writes.

No schema file is downloaded at test time and none of the packages available here ships the two
schemas, so these checks are written from the published definitions: the JUnit layout of Jenkins'
`junit-10.xsd` (the one Jenkins, GitLab and the GitHub test-report actions read) and the SARIF 2.1.0
JSON schema (OASIS, `sarif-schema-2.1.0.json`) for the objects the report uses, including its
`additionalProperties: false` rules. Each rule below names the element or definition it comes from.
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET

_INT = re.compile(r"^-?\d+$")
_DECIMAL = re.compile(r"^-?\d+(\.\d+)?$")

# element -> (required attributes, optional attributes, allowed children) as junit-10.xsd declares them
JUNIT = {
    "testsuites": (set(), {"name", "time", "tests", "failures", "errors", "disabled", "skipped"}, {"testsuite"}),
    "testsuite": ({"name", "tests"}, {"failures", "errors", "time", "disabled", "skipped", "timestamp", "hostname",
                                      "id", "package", "file", "log", "url", "version"},
                  {"properties", "testcase", "system-out", "system-err"}),
    "properties": (set(), set(), {"property"}),
    "property": ({"name", "value"}, set(), set()),
    "testcase": ({"name"}, {"assertions", "time", "classname", "status", "class", "file", "line"},
                 {"skipped", "error", "failure", "system-out", "system-err"}),
    "failure": (set(), {"type", "message"}, set()),
    "error": (set(), {"type", "message"}, set()),
    "skipped": (set(), {"message"}, set()),
    "system-out": (set(), set(), set()),
    "system-err": (set(), set(), set()),
}
JUNIT_INTS = {"tests", "failures", "errors", "disabled", "skipped", "line", "assertions"}
JUNIT_DECIMALS = {"time"}


def check_junit(text: str) -> list[str]:
    """Problems of a JUnit XML document (empty: valid)."""
    problems = []
    root = ET.fromstring(text.encode("utf-8"))
    if root.tag not in ("testsuites", "testsuite"):
        return [f"root element is <{root.tag}>, expected <testsuites> or <testsuite>"]

    def visit(el):
        rule = JUNIT.get(el.tag)
        if rule is None:
            problems.append(f"unknown element <{el.tag}>")
            return
        required, optional, children = rule
        for a in required - set(el.attrib):
            problems.append(f"<{el.tag}> lacks the required attribute '{a}'")
        for a, v in el.attrib.items():
            if a not in required | optional:
                problems.append(f"<{el.tag}> has the undeclared attribute '{a}'")
            if a in JUNIT_INTS and not _INT.match(v):
                problems.append(f"<{el.tag} {a}='{v}'> is not an integer")
            if a in JUNIT_DECIMALS and not _DECIMAL.match(v):
                problems.append(f"<{el.tag} {a}='{v}'> is not a decimal")
        if el.tag == "testcase" and len(el.findall("skipped")) > 1:
            problems.append("<testcase> has more than one <skipped>")
        if el.tag == "properties" and not len(el):
            problems.append("<properties> needs at least one <property>")
        for c in el:
            if c.tag not in children:
                problems.append(f"<{c.tag}> is not allowed inside <{el.tag}>")
            visit(c)
        if el.tag == "testsuite":
            cases = el.findall("testcase")
            for attr, child in (("tests", None), ("failures", "failure"), ("errors", "error"), ("skipped", "skipped")):
                if attr in el.attrib:
                    n = len(cases) if child is None else sum(1 for c in cases if c.find(child) is not None)
                    if int(el.attrib[attr]) != n:
                        problems.append(f"testsuite '{el.get('name')}': {attr}={el.attrib[attr]} but {n} found")

    visit(root)
    return problems


# SARIF 2.1.0: definition -> (required properties, allowed properties)
SARIF = {
    "sarifLog": ({"version", "runs"}, {"$schema", "version", "runs", "inlineExternalProperties", "properties"}),
    "run": ({"tool"}, {"tool", "invocations", "conversion", "language", "versionControlProvenance",
                       "originalUriBaseIds", "artifacts", "logicalLocations", "graphs", "results",
                       "automationDetails", "runAggregates", "baselineGuid", "redactionTokens",
                       "defaultEncoding", "defaultSourceLanguage", "newlineSequences", "columnKind",
                       "externalPropertyFileReferences", "threadFlowLocations", "taxonomies", "addresses",
                       "translations", "policies", "webRequests", "webResponses", "specialLocations",
                       "properties"}),
    "tool": ({"driver"}, {"driver", "extensions", "properties"}),
    "toolComponent": ({"name"}, {"guid", "name", "organization", "product", "productSuite", "shortDescription",
                                 "fullDescription", "fullName", "version", "semanticVersion", "dottedQuadFileVersion",
                                 "releaseDateUtc", "downloadUri", "informationUri", "globalMessageStrings",
                                 "notifications", "rules", "taxa", "locations", "language", "contents",
                                 "isComprehensive", "localizedDataSemanticVersion", "minimumRequiredLocalizedDataSemanticVersion",
                                 "associatedComponent", "translationMetadata", "supportedTaxonomies", "properties"}),
    "reportingDescriptor": ({"id"}, {"id", "deprecatedIds", "guid", "deprecatedGuids", "name", "deprecatedNames",
                                     "shortDescription", "fullDescription", "messageStrings",
                                     "defaultConfiguration", "helpUri", "help", "relationships", "properties"}),
    "multiformatMessageString": ({"text"}, {"text", "markdown", "properties"}),
    "result": ({"message"}, {"guid", "correlationGuid", "ruleId", "ruleIndex", "rule", "kind", "level", "message",
                             "analysisTarget", "locations", "hostedViewerUri", "relatedLocations", "stacks",
                             "codeFlows", "graphs", "graphTraversals", "suppressions", "baselineState", "rank",
                             "attachments", "workItemUris", "provenance", "fixes", "taxa", "webRequest",
                             "webResponse", "properties", "partialFingerprints", "fingerprints", "occurrenceCount"}),
    "message": (set(), {"text", "markdown", "id", "arguments", "properties"}),
    "location": (set(), {"id", "physicalLocation", "logicalLocations", "message", "annotations", "relationships",
                         "properties"}),
    "physicalLocation": (set(), {"address", "artifactLocation", "region", "contextRegion", "properties"}),
    "artifactLocation": (set(), {"uri", "uriBaseId", "index", "description", "properties"}),
    "region": (set(), {"startLine", "startColumn", "endLine", "endColumn", "charOffset", "charLength", "byteOffset",
                       "byteLength", "snippet", "message", "sourceLanguage", "properties"}),
}
LEVELS = {"none", "note", "warning", "error"}


def check_sarif(log) -> list[str]:
    """Problems of a SARIF log against the 2.1.0 schema's definitions for the objects it contains."""
    problems: list[str] = []

    def obj(o, kind: str, where: str) -> bool:
        if not isinstance(o, dict):
            problems.append(f"{where}: a {kind} must be an object")
            return False
        required, allowed = SARIF[kind]
        for k in required - set(o):
            problems.append(f"{where}: {kind} lacks '{k}'")
        for k in set(o) - allowed:
            problems.append(f"{where}: {kind} does not allow '{k}'")
        if "properties" in o and not isinstance(o["properties"], dict):
            problems.append(f"{where}: 'properties' must be a property bag (object)")
        return True

    if not obj(log, "sarifLog", "log"):
        return problems
    if log.get("version") != "2.1.0":
        problems.append(f"log: version must be '2.1.0', not {log.get('version')!r}")
    runs = log.get("runs")
    if not isinstance(runs, list):
        problems.append("log: runs must be an array")
        return problems
    for i, run in enumerate(runs):
        w = f"runs[{i}]"
        if not obj(run, "run", w):
            continue
        if obj(run.get("tool"), "tool", f"{w}.tool") and obj(run["tool"].get("driver"), "toolComponent",
                                                              f"{w}.tool.driver"):
            drv = run["tool"]["driver"]
            rules = drv.get("rules", [])
            for j, r in enumerate(rules):
                if obj(r, "reportingDescriptor", f"{w}.rules[{j}]") and "shortDescription" in r:
                    obj(r["shortDescription"], "multiformatMessageString", f"{w}.rules[{j}].shortDescription")
        else:
            rules = []
        for j, res in enumerate(run.get("results", [])):
            rw = f"{w}.results[{j}]"
            if not obj(res, "result", rw):
                continue
            if obj(res.get("message"), "message", f"{rw}.message") and not ({"text", "id"} & set(res["message"])):
                problems.append(f"{rw}.message needs 'text' or 'id'")
            if "level" in res and res["level"] not in LEVELS:
                problems.append(f"{rw}: level {res['level']!r} is not one of {sorted(LEVELS)}")
            if "ruleIndex" in res:
                ri = res["ruleIndex"]
                if not isinstance(ri, int) or ri < -1 or ri >= len(rules):
                    problems.append(f"{rw}: ruleIndex {ri!r} does not index tool.driver.rules")
                elif "ruleId" in res and rules[ri].get("id") != res["ruleId"]:
                    problems.append(f"{rw}: ruleId {res['ruleId']!r} differs from rules[{ri}].id")
            for k, loc in enumerate(res.get("locations", [])):
                lw = f"{rw}.locations[{k}]"
                if not obj(loc, "location", lw) or "physicalLocation" not in loc:
                    continue
                pl = loc["physicalLocation"]
                if not obj(pl, "physicalLocation", f"{lw}.physicalLocation"):
                    continue
                if not ({"address", "artifactLocation"} & set(pl)):
                    problems.append(f"{lw}.physicalLocation needs 'artifactLocation' or 'address'")
                if "artifactLocation" in pl and obj(pl["artifactLocation"], "artifactLocation", f"{lw}.artifactLocation"):
                    uri = pl["artifactLocation"].get("uri")
                    if uri is not None and (not isinstance(uri, str) or " " in uri and "%20" not in uri):
                        problems.append(f"{lw}: uri {uri!r} is not a URI reference")
                if "region" in pl and obj(pl["region"], "region", f"{lw}.region"):
                    for key in ("startLine", "startColumn", "endLine", "endColumn"):
                        v = pl["region"].get(key)
                        if v is not None and (not isinstance(v, int) or v < 1):
                            problems.append(f"{lw}.region.{key} must be an integer >= 1, not {v!r}")
    return problems
