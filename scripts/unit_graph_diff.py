#!/usr/bin/env python3
"""Which units of a second cargo build are not those of a first: the check behind the feature
names in crates/marsden-py/Cargo.toml (the Python extension built in CI must reuse what
`cargo test --workspace` compiled). A unit counts as shared when its package, target, mode,
features, profile settings and dependencies' units all agree.

    RUSTC_BOOTSTRAP=1 cargo test --workspace --no-run --unit-graph -Z unstable-options > a.json
    RUSTC_BOOTSTRAP=1 cargo rustc -p marsden-py --lib --profile dev --unit-graph -Z unstable-options > b.json
    scripts/unit_graph_diff.py a.json b.json      # RUSTC_BOOTSTRAP for this measurement only

Prints each unit of the second graph not in the first, with the features of the same package
in the first where its own dependencies are all shared (the root of a difference).
"""
import hashlib
import json
import sys


def unit_keys(path):
    """The units of a unit graph and, for each, a hash of everything that makes it shared."""
    units = json.load(open(path))["units"]
    memo = {}

    def key(i):
        if i not in memo:
            u = units[i]
            profile = {k: v for k, v in u["profile"].items() if k != "name"}
            own = json.dumps([u["pkg_id"], u["target"]["name"], u["target"]["kind"], u["mode"],
                              sorted(u["features"]), profile, u.get("platform")], sort_keys=True)
            deps = sorted(key(d["index"]) for d in u["dependencies"])
            memo[i] = hashlib.sha1((own + "|".join(deps)).encode()).hexdigest()
        return memo[i]

    return units, [key(i) for i in range(len(units))]


def main():
    first, first_keys = unit_keys(sys.argv[1])
    second, second_keys = unit_keys(sys.argv[2])
    shared = set(first_keys)
    for i, u in enumerate(second):
        if second_keys[i] in shared or u["mode"] == "run-custom-build":
            continue
        differing = [second[d["index"]]["pkg_id"].split("#")[-1] for d in u["dependencies"]
                     if second_keys[d["index"]] not in shared]
        print(u["pkg_id"].split("/")[-1], u["target"]["kind"], "features", u["features"],
              "differing dependencies", differing[:6])
        if differing:
            continue
        for v in first:
            if v["pkg_id"] == u["pkg_id"] and v["target"]["name"] == u["target"]["name"]:
                profile = {k: (v["profile"].get(k), u["profile"][k]) for k in u["profile"]
                           if k != "name" and v["profile"].get(k) != u["profile"][k]}
                print("   in the first graph: features", v["features"], "profile differences",
                      profile)


if __name__ == "__main__":
    main()
