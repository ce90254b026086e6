#!/usr/bin/env python3
"""Hostile inputs and kills against every shoal command (docs/reliability.md).

Feeds each command inputs a careless or hostile user could give it (scenario overrides and
files, damaged plan files, studies and shard tables, grids, waypoints, manifests planted in
output folders), and kills commands at random moments while they write. Every draw comes from
one seed, so a run is reproduced exactly by its seed.

For each command and input class it counts runs and outcomes:

- error:     a clean refusal (exit 1 or 2 with a message, no panic);
- accepted:  exit 0 (or a plan `shoal check` rightly refuses, exit 1 with VIOLATED);
- panic:     Rust panicked ("panicked at", exit 101);
- hang:      still running after the time limit (killed);
- abort:     ended by a signal (SIGABRT on allocation failure, SIGSEGV);
- wrong:     a wrong verdict: `shoal check` passing a plan with a constraint broken,
             `shoal plan` exiting 0 with a plan its own check refuses, `sweep collect` exiting 0
             with rows missing, or a random mission inside the documented ranges refused (the
             feasible missions: every one must plan and pass its check);
- touched:   a file outside the run's folder changed (the planted manifests aim at them);

and, for the kills: leftovers (shoal's hidden temporary files and staging folders still there
after the next run of the command), mixed sets (an output set part old and part new once a
reader has opened the folder) and rows lost (a sweep killed and resumed whose table differs from
an uninterrupted run's).

Usage:
    scripts/reliability.py [--shoal target/release/shoal] [--seed 1] [--inputs 1000]
                           [--kills 60] [--feasible 150] [--broken 115] [--work DIR]
                           [--json report.json]

Needs only Python 3.11's standard library. Exit status 1 when any panic, hang, abort, wrong
acceptance, touched file, leftover, mixed set or lost row was seen.
"""

from __future__ import annotations

import argparse
import collections
import csv
import hashlib
import io
import json
import os
import random
import shutil
import signal
import subprocess
import sys
import time
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
TIMEOUT = 90.0  # seconds: a command that runs longer is a hang

# Hostile values for `--set key=value` and for scenario files: wrong types, out of range,
# non-finite, absurdly large or small, text with escapes and paths.
VALUES = [
    "nan", "inf", "-inf", "1e308", "-1e308", "1e-300", "-1e-300", "0", "-0.0", "-1", "1e9",
    "-1e9", "18446744073709551616", "9223372036854775807", "-9223372036854775808", "2.5", "0.5",
    "true", '"x"', '""', "[]", "[1, 2, 3]", "[nan, 1]", "[1e308, 1e308]", "{ a = 1 }",
    '"\\u001b[31mred\\u001b[0m"', '"../outside/victim.txt"', "1_000", "0x10", "1e-9", "100000",
    "3", "7", "65", "1000", "0.001", "[0.3, 0]", "[0.5, 0.2]", "[-1, -1]",
]

# Hostile JSON values for plan files.
JSON_VALUES = [
    1e308, -1e308, 0, -1, None, "x", [], {}, True, 1e-300, 10**20, -(10**20), 0.5, 3, 1000,
    "\u001b[2J\u001b[31m", [1e308] * 3,
]


class Harness:
    def __init__(self, shoal: Path, seed: int, work: Path):
        self.shoal = str(shoal)
        self.rng = random.Random(seed)
        self.seed = seed
        self.work = work
        self.table: dict[tuple[str, str], collections.Counter] = collections.defaultdict(
            collections.Counter)
        self.kills: dict[str, collections.Counter] = collections.defaultdict(collections.Counter)
        self.examples: list[dict] = []
        self.n = 0
        self.outside = work / "outside"
        self.restore_outside()

    # ----- running -------------------------------------------------------------------------

    @staticmethod
    def snapshot(root: Path) -> dict:
        out = {}
        for p in sorted(root.rglob("*")):
            st = p.lstat()
            data = p.read_bytes() if p.is_file() and not p.is_symlink() else b""
            out[str(p.relative_to(root))] = (st.st_mode, st.st_size, st.st_mtime_ns,
                                             hashlib.sha256(data).hexdigest())
        return out

    def sandbox(self) -> Path:
        self.n += 1
        d = self.work / f"run{self.n:05d}"
        d.mkdir()
        return d

    def run(self, args: list[str], cwd: Path, timeout: float = TIMEOUT, env=None):
        start = time.monotonic()
        try:
            p = subprocess.run([self.shoal, *args], cwd=cwd, capture_output=True,
                               timeout=timeout, env=env)
            return p.returncode, p.stdout.decode("utf-8", "replace"), \
                p.stderr.decode("utf-8", "replace"), time.monotonic() - start
        except subprocess.TimeoutExpired:
            return None, "", "", time.monotonic() - start

    def record(self, command: str, klass: str, args: list[str], rc, err: str,
               wrong: bool = False, accept_codes=(0,)):
        c = self.table[(command, klass)]
        c["runs"] += 1
        if rc is None:
            kind = "hang"
        elif "panicked at" in err or rc == 101:
            kind = "panic"
        elif rc < 0 or "memory allocation" in err:
            kind = "abort"
        elif wrong:
            kind = "wrong"
        elif rc in accept_codes:
            kind = "accepted"
        elif rc in (1, 2, 130) and err.strip():
            kind = "error"
        elif rc == 1:
            kind = "error"
        else:
            kind = "abort"
        c[kind] += 1
        if self.snapshot(self.outside) != self.fingerprint:
            c["touched"] += 1
            kind = "touched"
            shutil.rmtree(self.outside)
            self.restore_outside()
        if kind in ("hang", "panic", "abort", "wrong", "touched"):
            self.examples.append({"command": command, "class": klass, "kind": kind,
                                  "args": args, "rc": rc, "stderr": err[-600:]})
        return kind

    def restore_outside(self):
        for name in ["victim.txt", "plan.json", "usv.csv", "auv0.csv", "sim.json",
                     "keep/inner.txt", "figures/depth.png", "floor.prj"]:
            p = self.outside / name
            p.parent.mkdir(parents=True, exist_ok=True)
            p.write_text(f"the user's own {name}\n")
        self.fingerprint = self.snapshot(self.outside)

    # ----- fixtures --------------------------------------------------------------------------

    def fixtures(self):
        f = self.work / "fixtures"
        f.mkdir()
        self.fx = f
        small = ["--set", "team.auvs=2", "--set", "horizon.steps=5"]
        rc, _, err, _ = self.run(["plan", "-q", "--no-plot", "-o", "plan", *small], f)
        assert rc == 0, err
        self.plan_text = (f / "plan/plan.json").read_text()
        # a larger plan (the default scenario, three windows) for the commands that are quick
        rc, _, err, _ = self.run(["plan", "-q", "--no-plot", "-o", "big", "--set", "windows=3"],
                                 f)
        assert rc == 0, err
        self.big_plan_text = (f / "big/plan.json").read_text()
        self.plan = json.loads(self.plan_text)
        rc, _, err, _ = self.run(["simulate", "plan/plan.json", "--no-plot", "-o", "sim.json"], f)
        assert rc == 0, err
        self.sim_text = (f / "sim.json").read_text()
        rc, out, err, _ = self.run(["init", "mission.toml"], f)
        assert rc == 0, err
        self.scenario_text = (f / "mission.toml").read_text()
        self.keys = sorted(flatten(tomllib.loads(self.scenario_text)))
        rc, _, err, _ = self.run(["seafloor", "export", "-o", "floor.asc",
                                  "--set", "seafloor.synthetic.size=[2000,2000]"], f)
        assert rc == 0, err
        self.grid_text = (f / "floor.asc").read_text()
        # a small study and its two shard tables
        (f / "study.toml").write_text(
            'method = "mpc"\n[set]\n"horizon.steps" = 4\n[axes]\nseed = "1..4"\n'
            '"team.auvs" = [1, 2]\n')
        for i in range(2):
            rc, _, err, _ = self.run(["sweep", "--quiet", "study.toml", "-o", "sweep",
                                      "--shard", f"{i}/2"], f)
            assert rc == 0, err
        self.shards = {p.name: p.read_text() for p in sorted((f / "sweep").glob("shard-*.csv"))}
        self.sweep_extra = {p.name: p.read_bytes() for p in sorted((f / "sweep").iterdir())
                            if p.is_file() and not p.name.startswith("shard-")}
        rc, _, err, _ = self.run(["sweep", "collect", "sweep"], f)
        assert rc == 0, err
        self.study_rows = len(list(csv.DictReader(io.StringIO((f / "sweep/runs.csv").read_text()))))
        # waypoints from the plan: every vehicle's positions
        w = self.plan["windows"][0]["final"]
        self.waypoints = {
            "format": "shoal-waypoints/1", "method": "test",
            "usv": [p for p in w["usv"]["position"]],
            "auvs": [[p for p in a["position"]] for a in w["auvs"]],
        }

    # ----- input classes ---------------------------------------------------------------------

    def set_overrides(self, count: int):
        base = ["-q", "--no-plot", "--set", "team.auvs=2", "--set", "horizon.steps=4"]
        for _ in range(count):
            d = self.sandbox()
            sets = []
            for _ in range(self.rng.choice([1, 1, 1, 2, 3])):
                key = self.rng.choice(self.keys + ["nosuch.key", "team", "auv.", ".x", "seed"])
                sets += ["--set", f"{key}={self.rng.choice(VALUES)}"]
            self.plan_then_check(["plan", *base, "-o", "out", *sets], d, "--set values")

    def plan_then_check(self, args: list, d: Path, cls: str):
        """Runs `shoal plan` with `args` in the sandbox `d`; a plan it writes must pass the check
        of the written file (else a wrong verdict). Records the run and removes the sandbox."""
        rc, _, err, _ = self.run(args, d)
        wrong = False
        if rc == 0:
            rc2, _, _, _ = self.run(["check", "out/plan.json"], d)
            wrong = rc2 != 0
        self.record("plan", cls, args, rc, err, wrong)
        shutil.rmtree(d)

    def scenario_files(self, count: int):
        lines = self.scenario_text.splitlines()
        for _ in range(count):
            d = self.sandbox()
            mutated = list(lines)
            for _ in range(self.rng.choice([1, 2, 3])):
                op = self.rng.choice(["value", "value", "delete", "dup", "garbage", "truncate",
                                      "unknown"])
                i = self.rng.randrange(len(mutated))
                if op == "value":
                    idx = [j for j, l in enumerate(mutated) if "=" in l and not l.startswith("#")]
                    if idx:
                        j = self.rng.choice(idx)
                        k = mutated[j].split("=", 1)[0]
                        mutated[j] = f"{k}= {self.rng.choice(VALUES)}"
                elif op == "delete":
                    del mutated[i]
                elif op == "dup":
                    mutated.insert(i, mutated[i])
                elif op == "garbage":
                    mutated.insert(i, self.rng.choice(["[[x]]", "= 3", "\x00\x01", "a.b.c = {",
                                                       "[auv]", "windows = 1e3"]))
                elif op == "truncate":
                    mutated = mutated[:i]
                else:
                    mutated.insert(i, "frobnicate = 3")
            text = "\n".join(mutated) + "\n"
            text = text.replace("auvs = 5", "auvs = 2").replace("steps = 20", "steps = 4")
            (d / "m.toml").write_text(text)
            self.plan_then_check(["plan", "m.toml", "-q", "--no-plot", "-o", "out"], d,
                                 "scenario files")

    def feasible(self, count: int):
        """Random missions inside the documented ranges: each must plan (exit 0) and pass the
        check of the written file; a refusal here is counted as a wrong refusal."""
        for _ in range(count):
            d = self.sandbox()
            sets = [f"seed={self.rng.randrange(1, 10**6)}",
                    f"team.auvs={self.rng.choice([1, 2, 3, 4])}",
                    f"horizon.steps={self.rng.randrange(4, 11)}",
                    f"windows={self.rng.choice([1, 1, 2])}",
                    # a REMUS (its cruise floor, 1.25 m/s) or a slow vehicle without one
                    *self.rng.choice([["auv.max_speed=1.5"], ["auv.max_speed=2.0"],
                                      ["auv.max_speed=0.52", "auv.min_speed=0"],
                                      ["auv.max_speed=1.0", "auv.min_speed=0"]]),
                    f"acoustic.sonar_range={self.rng.choice([150, 200, 300])}",
                    f"auv.floor_clearance={self.rng.choice([3, 5, 8])}"]
            args = ["plan", "-q", "--no-plot", "-o", "out"] + [a for x in sets
                                                                 for a in ("--set", x)]
            rc, _, err, _ = self.run(args, d)
            refused = rc != 0
            if rc == 0:
                rc2, _, _, _ = self.run(["check", "out/plan.json"], d)
                refused = rc2 != 0
            c = self.table[("plan", "random feasible missions")]
            c["runs"] += 1
            c["accepted" if not refused else "wrong"] += 1
            if refused:
                self.examples.append({"command": "plan", "kind": "wrong refusal",
                                      "args": args, "rc": rc, "stderr": err[-400:]})
            shutil.rmtree(d)

    def broken(self, count: int):
        """Whole, readable plans with one constraint broken: `shoal check` must refuse each."""
        for i in range(count):
            d = self.sandbox()
            p = json.loads(self.plan_text)
            w = self.rng.choice(p["windows"])
            auv = self.rng.choice(w["final"]["auvs"])
            k = self.rng.randrange(1, len(auv["position"]))
            how = ["moved", "under the floor", "too fast", "limit lowered", "above the surface",
                   "far from the USV"][i % 6]
            if how == "moved":
                auv["position"][k][self.rng.randrange(2)] += self.rng.choice([-200.0, 200.0])
            elif how == "under the floor":
                auv["position"][k][2] = -1000.0
            elif how == "too fast":
                auv["velocity"][k] = [10.0 * v for v in auv["velocity"][k]]
            elif how == "limit lowered":
                p["scenario"]["auv"]["max_speed"] = 0.05
            elif how == "above the surface":
                auv["position"][k][2] = 5.0
            else:
                for q in auv["position"][k:]:
                    q[0] += 2000.0
            (d / "plan.json").write_text(json.dumps(p))
            args = ["check", "plan.json"]
            rc, out, err, _ = self.run(args, d)
            self.record("check", "broken plans (must refuse)", args, rc, err + out[-200:],
                        wrong=rc == 0)
            shutil.rmtree(d)

    def mutated_plan(self) -> tuple[str, bool]:
        """A damaged plan file's text, and whether `shoal check` must refuse it."""
        op = self.rng.choice(["leaf", "leaf", "leaf", "move", "move", "delete", "truncate",
                              "flip", "grow"])
        if op == "truncate":
            return self.plan_text[: self.rng.randrange(len(self.plan_text))], False
        if op == "flip":
            b = bytearray(self.plan_text.encode())
            for _ in range(self.rng.choice([1, 5, 20])):
                b[self.rng.randrange(len(b))] = self.rng.randrange(256)
            return b.decode("utf-8", "replace"), False
        p = json.loads(self.plan_text)
        if op == "move":
            w = self.rng.choice(p["windows"])
            who = self.rng.choice(w["final"]["auvs"] + [w["final"]["usv"]])
            k = self.rng.randrange(1, len(who["position"]))
            who["position"][k][self.rng.randrange(2)] += self.rng.choice([-500.0, 500.0])
            return json.dumps(p), True
        paths = leaves(p)
        path = self.rng.choice(paths)
        parent = p
        for key in path[:-1]:
            parent = parent[key]
        if op == "delete" and isinstance(parent, dict):
            del parent[path[-1]]
        elif op == "grow" and isinstance(parent, list):
            parent.extend([parent[-1]] * self.rng.choice([1, 10, 1000]))
        else:
            parent[path[-1]] = self.rng.choice(JSON_VALUES)
        return json.dumps(p), False

    def plan_files(self, command: str, count: int):
        for _ in range(count):
            d = self.sandbox()
            text, must_refuse = self.mutated_plan()
            (d / "plan.json").write_text(text)
            extra = []
            if command == "simulate":
                extra = ["--no-plot", "--set", f"simulation.step={self.rng.choice(['0.05', '0.1', '1e-9', '0', '-1', 'nan', '1e300'])}"] \
                    if self.rng.random() < 0.3 else ["--no-plot"]
                args = ["simulate", "plan.json", *extra]
            elif command == "check":
                args = ["check", "plan.json"]
            elif command == "view":
                args = ["view", "plan.json", "-o", "out/m.html"]
            elif command == "export":
                args = ["export", "plan.json", "out/p.csv"]
            else:
                args = ["plot", "plan.json", "-o", "out/figures"]
            rc, out, err, _ = self.run(args, d)
            # check refuses with exit 1 and VIOLATED: a clean refusal
            wrong = command == "check" and must_refuse and rc == 0
            self.record(command, "damaged plan files", args, rc, err + out[-200:], wrong)
            shutil.rmtree(d)

    def sim_files(self, count: int):
        """`view --sim` with damaged sim.json files."""
        for _ in range(count):
            d = self.sandbox()
            (d / "plan.json").write_text(self.plan_text)
            text = self.sim_text
            op = self.rng.choice(["truncate", "flip", "leaf"])
            if op == "truncate":
                text = text[: self.rng.randrange(len(text))]
            elif op == "flip":
                b = bytearray(text.encode())
                b[self.rng.randrange(len(b))] = self.rng.randrange(256)
                text = b.decode("utf-8", "replace")
            else:
                s = json.loads(text)
                path = self.rng.choice(leaves(s))
                parent = s
                for key in path[:-1]:
                    parent = parent[key]
                parent[path[-1]] = self.rng.choice(JSON_VALUES)
                text = json.dumps(s)
            (d / "sim.json").write_text(text)
            args = ["view", "plan.json", "--sim", "sim.json", "-o", "m.html"]
            rc, _, err, _ = self.run(args, d)
            self.record("view", "damaged sim files", args, rc, err)
            shutil.rmtree(d)

    def studies(self, count: int):
        axes = [
            'seed = "0..1000000000000"', 'seed = "-9223372036854775808..9223372036854775807"',
            'seed = "1..3"', 'seed = "3..1"', 'seed = "a..b"', "seed = []", "seed = [1, 2]",
            '"team.auvs" = [1, 1000]', '"team.auvs" = [0]', '"horizon.steps" = [3, "x"]',
            '"nosuch.key" = [1]', '"seafloor.file" = ["../outside/victim.txt"]',
            '"seafloor.file" = ["/dev/zero"]', 'seed = "0..65535"',
            '"horizon.dt" = [1e-300]', '"simulation.step" = [1e-9]',
        ]
        heads = ['', 'method = "simplex"\n', 'scenario = "nosuch.toml"\n', 'simulate = 3\n',
                 'keep_plans = true\n', 'scenario = "../outside/victim.txt"\n', 'runs = 3\n']
        for _ in range(count):
            d = self.sandbox()
            picked = self.rng.sample(axes, self.rng.choice([1, 2, 4]))
            if self.rng.random() < 0.2:  # the product overflows
                picked = [f'"k{i}" = "0..65535"' for i in range(4)]
            text = (self.rng.choice(heads) + '[set]\n"horizon.steps" = 4\n"team.auvs" = 1\n'
                    "[axes]\n" + "\n".join(dict.fromkeys(picked)) + "\n")
            (d / "study.toml").write_text(text)
            args = ["sweep", "--quiet", "study.toml", "-o", "out"]
            rc, _, err, _ = self.run(args, d, timeout=60)
            if rc is None:
                # a legitimate study of many small runs is not a hang if it was making progress
                table = d / "out/runs.csv"
                if table.exists() and table.stat().st_size > 0:
                    rc, err = 0, ""
            self.record("sweep", "hostile studies", args, rc, err)
            shutil.rmtree(d)

    def collects(self, count: int):
        for _ in range(count):
            d = self.sandbox()
            sw = d / "sweep"
            sw.mkdir()
            for name, data in self.sweep_extra.items():
                if name != "runs.csv" and not name.startswith("runs."):
                    (sw / name).write_bytes(data)
            texts = dict(self.shards)
            name = self.rng.choice(sorted(texts))
            lines = texts[name].splitlines(keepends=True)
            op = self.rng.choice(["truncate", "drop", "dup", "field", "empty", "header",
                                  "garbage", "index", "remove", "swap"])
            if op == "truncate":
                t = texts[name]
                texts[name] = t[: self.rng.randrange(1, len(t))]
            elif op == "drop" and len(lines) > 1:
                del lines[self.rng.randrange(1, len(lines))]
                texts[name] = "".join(lines)
            elif op == "dup" and len(lines) > 1:
                lines.append(lines[self.rng.randrange(1, len(lines))])
                texts[name] = "".join(lines)
            elif op == "field" and len(lines) > 1:
                i = self.rng.randrange(1, len(lines))
                cells = lines[i].rstrip("\n").split(",")
                cells[self.rng.randrange(len(cells))] = self.rng.choice(["", "x", "nan", "1e999",
                                                                          '"', "a,b"])
                lines[i] = ",".join(cells) + "\n"
                texts[name] = "".join(lines)
            elif op == "empty":
                texts[name] = ""
            elif op == "header":
                texts[name] = lines[0]
            elif op == "garbage":
                texts[name] = texts[name] + "\x00\x01garbage\n"
            elif op == "index" and len(lines) > 1:
                i = self.rng.randrange(1, len(lines))
                cells = lines[i].split(",")
                cells[0] = self.rng.choice(["999", "-1", "x", "1"])
                lines[i] = ",".join(cells)
                texts[name] = "".join(lines)
            elif op == "remove":
                del texts[name]
            elif op == "swap" and len(lines) > 1:
                head = lines[0].rstrip("\n").split(",")
                head[1], head[2] = head[2], head[1]
                lines[0] = ",".join(head) + "\n"
                texts[name] = "".join(lines)
            for n, t in texts.items():
                (sw / n).write_text(t)
            args = ["sweep", "collect", "sweep"]
            rc, _, err, _ = self.run(args, d)
            wrong = False
            if rc == 0:
                try:
                    rows = list(csv.DictReader(io.StringIO((sw / "runs.csv").read_text())))
                    runs = sorted(int(r["run"]) for r in rows)
                    wrong = runs != list(range(self.study_rows))
                except Exception:
                    wrong = True
            self.record("sweep collect", "damaged shard tables", args, rc, err, wrong)
            shutil.rmtree(d)

    def compares(self, count: int):
        seeds = ["1-1000000000", "1-2", "2-1", "x", "", "1,2,x", "18446744073709551616",
                 "0-18446744073709551615", "1--2", "-1", "1,,2", "1-1"]
        auvs = ["1", "0", "1000", "x", "1,1", "-1", "99999999999999999999"]
        for _ in range(count):
            d = self.sandbox()
            args = ["compare", "--no-plot", "--set", "horizon.steps=4", "--methods", "mpc",
                    "--seeds", self.rng.choice(seeds), "--auvs", self.rng.choice(auvs),
                    "-o", "out"]
            rc, _, err, _ = self.run(args, d, timeout=60)
            self.record("compare", "hostile seeds and teams", args, rc, err)
            shutil.rmtree(d)

    def grids(self, count: int):
        lines = self.grid_text.splitlines(keepends=True)
        for _ in range(count):
            d = self.sandbox()
            mutated = list(lines)
            op = self.rng.choice(["header", "header", "value", "truncate", "rows", "flip"])
            if op == "header":
                i = self.rng.randrange(6)
                key = mutated[i].split()[0]
                mutated[i] = f"{key} {self.rng.choice(['0', '-1', '1e308', 'nan', 'x', '99999999999', '1e-300', ''])}\n"
            elif op == "value":
                i = self.rng.randrange(6, len(mutated))
                cells = mutated[i].split()
                cells[self.rng.randrange(len(cells))] = self.rng.choice(["nan", "x", "1e308", "-9999"])
                mutated[i] = " ".join(cells) + "\n"
            elif op == "truncate":
                mutated = mutated[: self.rng.randrange(len(mutated))]
            elif op == "rows":
                del mutated[self.rng.randrange(6, len(mutated))]
            text = "".join(mutated)
            if op == "flip":
                b = bytearray(text.encode())
                b[self.rng.randrange(len(b))] = self.rng.randrange(256)
                (d / "g.asc").write_bytes(bytes(b))
            else:
                (d / "g.asc").write_text(text)
            which = self.rng.choice(["info", "export", "plan"])
            if which == "info":
                args = ["seafloor", "info", "g.asc"]
            elif which == "export":
                args = ["seafloor", "export", "--from", "g.asc", "-o", "out/g2.asc"]
            else:
                args = ["plan", "-q", "--no-plot", "--seafloor", "g.asc", "--set", "team.auvs=1",
                        "--set", "horizon.steps=4", "--set", "seafloor.origin=[0,0]", "-o", "out"]
            rc, _, err, _ = self.run(args, d)
            self.record(f"seafloor {which}" if which != "plan" else "plan",
                        "damaged grid files", args, rc, err)
            shutil.rmtree(d)

    def waypoint_files(self, count: int):
        for _ in range(count):
            d = self.sandbox()
            w = json.loads(json.dumps(self.waypoints))
            path = self.rng.choice(leaves(w))
            parent = w
            for key in path[:-1]:
                parent = parent[key]
            parent[path[-1]] = self.rng.choice(JSON_VALUES)
            (d / "w.json").write_text(json.dumps(w))
            args = ["plan", "-q", "--no-plot", "--waypoints", "w.json", "--set", "team.auvs=2",
                    "--set", "horizon.steps=5", "-o", "out"]
            rc, _, err, _ = self.run(args, d)
            wrong = False
            if rc == 0:
                rc2, _, _, _ = self.run(["check", "out/plan.json"], d)
                wrong = rc2 not in (0, 1)
            self.record("plan", "damaged waypoint files", args, rc, err, wrong,
                        accept_codes=(0, 1))
            shutil.rmtree(d)

    def planted(self, count: int):
        """Manifests, journals and links planted in output folders, aimed outside them."""
        for _ in range(count):
            d = self.sandbox()
            out = d / "out"
            out.mkdir()
            target = os.path.relpath(self.outside, out)
            victim = self.rng.choice(["victim.txt", "plan.json", "usv.csv", "keep/inner.txt",
                                      "figures/depth.png", "auv0.csv"])
            choice = self.rng.choice(["relative", "absolute", "dotdot-figures", "link-figures",
                                      "link-file", "journal", "damaged", "link-manifest"])
            files = ["plan.json"]
            if choice == "relative":
                files.append(f"{target}/{victim}")
            elif choice == "absolute":
                files.append(str(self.outside / victim))
            elif choice == "dotdot-figures":
                files.append(f"figures/../{target}/{victim}")
            elif choice == "link-figures":
                os.symlink(self.outside / "figures", out / "figures")
                files.append("figures/depth.png")
            elif choice == "link-file":
                os.symlink(self.outside / "usv.csv", out / "usv.csv")
                files.append("usv.csv")
            elif choice == "journal":
                st = out / ".shoal-staging-host-1-abcdef"
                st.mkdir()
                (st / ".shoal-commit.json").write_text(json.dumps({
                    "kind": "plan", "files": [], "remove": [f"{target}/{victim}"],
                    "check_passed": True}))
            elif choice == "link-manifest":
                os.symlink(self.outside / victim, out / ".shoal-outputs.json")
            if choice == "damaged":
                (out / ".shoal-outputs.json").write_text('{"files": ["../')
            elif choice not in ("journal", "link-manifest"):
                (out / ".shoal-outputs.json").write_text(json.dumps(
                    {"files": files, "check_passed": True}))
            which = self.rng.choice(["plan", "plan", "simulate", "seafloor export"])
            if which == "plan":
                args = ["plan", "-q", "--set", "team.auvs=1", "--set", "horizon.steps=4",
                        "-o", "out"]
            elif which == "simulate":
                (d / "plan.json").write_text(self.plan_text)
                args = ["simulate", "plan.json", "-o", "out/sim.json"]
            else:
                args = ["seafloor", "export", "--set", "seafloor.synthetic.size=[2000,2000]",
                        "-o", "out/floor.asc"]
            rc, _, err, _ = self.run(args, d)
            self.record(which, "planted manifests and links", args, rc, err)
            shutil.rmtree(d)

    # ----- kills -----------------------------------------------------------------------------

    def kill_at(self, args: list[str], cwd: Path, after: float):
        p = subprocess.Popen([self.shoal, *args], cwd=cwd, stdout=subprocess.DEVNULL,
                             stderr=subprocess.DEVNULL)
        try:
            p.wait(timeout=after)
            return False  # it ended before the kill
        except subprocess.TimeoutExpired:
            p.send_signal(self.rng.choice([signal.SIGKILL, signal.SIGKILL, signal.SIGINT]))
            try:
                p.wait(timeout=TIMEOUT)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait()
                self.kills["hang after SIGINT"]["count"] += 1
            return True

    def timed(self, args: list[str], cwd: Path) -> float:
        start = time.monotonic()
        rc, _, err, _ = self.run(args, cwd)
        assert rc == 0, (args, err)
        return time.monotonic() - start

    @staticmethod
    def age(root: Path, files: list[str]):
        """Mark the files of an earlier set as old (mtime in 2001)."""
        for f in files:
            p = root / f
            if p.exists():
                os.utime(p, (1e9, 1e9))

    @staticmethod
    def leftovers(root: Path) -> list[str]:
        return [str(p.relative_to(root)) for p in root.rglob(".shoal-*")
                if p.name != ".shoal-outputs.json"]

    def set_state(self, root: Path, names: set[str]) -> str:
        """'old', 'new', 'none' or 'mixed' for the output set `names` (relative to root):
        old files have mtime 1e9."""
        have = [root / n for n in names if (root / n).exists()]
        if not have:
            return "none"
        ages = {"old" if abs(p.stat().st_mtime - 1e9) < 1 else "new" for p in have}
        if len(ages) == 2:
            return "mixed"
        return ages.pop()

    def kill_command(self, name: str, count: int, make):
        """Kill `count` runs of a command at random moments. `make(d)` prepares folder d (an
        earlier set, aged), and returns (args, set_of_old, set_of_new, reader_args)."""
        probe = self.sandbox()
        args, _, _, _ = make(probe)
        duration = self.timed(args, probe)
        shutil.rmtree(probe)
        for _ in range(count):
            # a kill drawn after the command ended is drawn again, earlier (at most 4 times)
            scale = 1.0
            for _attempt in range(4):
                d = self.sandbox()
                args, old, new, reader = make(d)
                # half the kills anywhere in the run, half in its last fifth (where it writes)
                frac = self.rng.random() if self.rng.random() < 0.5 else \
                    0.8 + 0.25 * self.rng.random()
                killed = self.kill_at(args, d, max(0.005, scale * frac * duration))
                if killed or _attempt == 3:
                    break
                shutil.rmtree(d)
                scale *= 0.5
            c = self.kills[name]
            c["kills"] += 1
            c["landed"] += killed
            c["pending"] += any(p.name == ".shoal-commit.json" for p in d.rglob("*"))
            if reader:
                self.run(reader, d)
            state_old = self.set_state(d, old)
            state_new = self.set_state(d, new)
            # the earlier set whole and untouched, or the new set whole
            whole_old = state_old == "old" and all((d / f).exists() for f in old) and \
                state_new in ("old", "none")
            whole_new = state_new == "new" and all((d / f).exists() for f in new) and \
                all(not (d / f).exists() for f in old - new)
            if not (whole_old or whole_new):
                c["mixed"] += 1
                self.examples.append({"command": name, "kind": "mixed", "args": args,
                                      "old": state_old, "new": state_new,
                                      "files": sorted(str(p.relative_to(d)) for p in d.rglob("*"))})
            # the next run of the command cleans up after the killed one
            rc, _, err, _ = self.run(args, d)
            left = self.leftovers(d)
            if left or rc != 0:
                c["leftovers"] += 1
                self.examples.append({"command": name, "kind": "leftover", "args": args,
                                      "left": left, "rc": rc, "stderr": err[-300:]})
            shutil.rmtree(d)

    def kills_all(self, total: int):
        per = max(1, total // 8)

        def plan(d):
            small = ["--set", "horizon.steps=5"]
            rc, _, err, _ = self.run(["plan", "-q", "-o", "out", "--set", "team.auvs=3", *small], d)
            assert rc == 0, err
            old = {str(p.relative_to(d)) for p in (d / "out").rglob("*")
                   if p.is_file() and not p.name.startswith(".")}
            self.age(d, sorted(old))
            new = {"out/plan.json", "out/usv.csv", "out/auv0.csv", "out/auv1.csv"} | \
                {f for f in old if f.startswith("out/figures/")}
            return (["plan", "-q", "-o", "out", "--set", "team.auvs=2", *small], old, new,
                    ["check", "out/plan.json"])

        def plan_windows(d):
            args, old, new, reader = plan(d)
            return args + ["--set", "windows=3"], old, new, reader

        def simulate(d):
            (d / "plan.json").write_text(self.plan_text)
            rc, _, err, _ = self.run(["simulate", "plan.json"], d)
            assert rc == 0, err
            old = {"sim.json", "figures/sim-error.png", "figures/sim-error.svg",
                   "figures/sim-tracks.png", "figures/sim-tracks.svg"}
            self.age(d, sorted(old))
            return ["simulate", "plan.json", "--no-plot"], old, {"sim.json"}, \
                ["view", "plan.json", "--sim", "sim.json", "-o", "m.html"]

        def grid(d):
            rc, _, err, _ = self.run(["seafloor", "export", "--from",
                                      str(ROOT / "examples/bathymetry/abrolhos.tif"), "-o",
                                      "floor.asc"], d)
            assert rc == 0, err
            old = {"floor.asc", "floor.prj"}
            self.age(d, sorted(old))
            return ["seafloor", "export", "-o", "floor.asc"], old, {"floor.asc"}, \
                ["seafloor", "info", "floor.asc"]

        def view(d):
            (d / "plan.json").write_text(self.big_plan_text)
            (d / "m.html").write_text("old")
            self.age(d, ["m.html"])
            return ["view", "plan.json", "-o", "m.html"], {"m.html"}, {"m.html"}, None

        def export(d):
            (d / "plan.json").write_text(self.big_plan_text)
            (d / "p.csv").write_text("old")
            self.age(d, ["p.csv"])
            return ["export", "plan.json", "p.csv"], {"p.csv"}, {"p.csv"}, None

        def compare(d):
            args = ["compare", "--no-plot", "--set", "horizon.steps=4", "--methods", "mpc",
                    "--seeds", "1-3", "--auvs", "1", "-o", "out"]
            rc, _, err, _ = self.run(args, d)
            assert rc == 0, err
            old = {"out/runs.csv", "out/summary.md"}
            self.age(d, sorted(old))
            return args, old, old, None

        self.kill_command("plan", per * 2, plan)
        self.kill_command("plan (3 windows)", per, plan_windows)
        self.kill_command("simulate", per, simulate)
        self.kill_command("seafloor export", per, grid)
        self.kill_command("view", per // 2 + 1, view)
        self.kill_command("export", per // 2 + 1, export)
        self.kill_command("compare", per // 2 + 1, compare)
        self.kill_sweeps(per)

    def kill_sweeps(self, count: int):
        """Kill a sweep, resume it, and compare its table with an uninterrupted run's."""
        d0 = self.sandbox()
        shutil.copy(self.fx / "study.toml", d0 / "study.toml")
        duration = self.timed(["sweep", "--quiet", "study.toml", "-o", "out"], d0)
        reference = rows_of(d0 / "out/runs.csv")
        for _ in range(count):
            d = self.sandbox()
            shutil.copy(self.fx / "study.toml", d / "study.toml")
            args = ["sweep", "--quiet", "study.toml", "-o", "out"]
            killed = self.kill_at(args, d, max(0.005, 0.9 * self.rng.random() * duration))
            c = self.kills["sweep (then --resume)"]
            c["kills"] += 1
            c["landed"] += killed
            rc, _, err, _ = self.run(args + ["--resume"], d)
            table = d / "out/runs.csv"
            if rc != 0 or not table.exists() or rows_of(table) != reference:
                c["rows lost"] += 1
                self.examples.append({"command": "sweep", "kind": "rows lost", "rc": rc,
                                      "stderr": err[-300:]})
            if self.leftovers(d):
                c["leftovers"] += 1
            shutil.rmtree(d)

    # ----- report ----------------------------------------------------------------------------

    def report(self) -> tuple[str, bool]:
        lines = ["| command | input class | runs | errors | accepted | panics | hangs | aborts "
                 "| wrong verdicts | files touched outside |",
                 "|---|---|---|---|---|---|---|---|---|---|"]
        total = collections.Counter()
        for (cmd, klass), c in sorted(self.table.items()):
            total.update(c)
            lines.append(f"| {cmd} | {klass} | {c['runs']} | {c['error']} | {c['accepted']} | "
                         f"{c['panic']} | {c['hang']} | {c['abort']} | {c['wrong']} | "
                         f"{c['touched']} |")
        lines.append(f"| **all** | | **{total['runs']}** | {total['error']} | "
                     f"{total['accepted']} | {total['panic']} | {total['hang']} | "
                     f"{total['abort']} | {total['wrong']} | {total['touched']} |")
        lines += ["", "| command killed | kills | landed | cut while moving the set | mixed sets "
                  "| leftovers after the next run | rows lost |", "|---|---|---|---|---|---|---|"]
        k = collections.Counter()
        for name, c in self.kills.items():
            k.update(c)
            lines.append(f"| {name} | {c['kills']} | {c['landed']} | {c['pending']} | "
                         f"{c['mixed']} | {c['leftovers']} | {c['rows lost']} |")
        lines.append(f"| **all** | **{k['kills']}** | {k['landed']} | {k['pending']} | "
                     f"{k['mixed']} | {k['leftovers']} | {k['rows lost']} |")
        bad = sum(total[x] for x in ["panic", "hang", "abort", "wrong", "touched"]) + \
            sum(k[x] for x in ["mixed", "leftovers", "rows lost", "count"])
        return "\n".join(lines), bad == 0


def flatten(d: dict, prefix: str = "") -> list[str]:
    keys = []
    for k, v in d.items():
        if isinstance(v, dict):
            keys += flatten(v, f"{prefix}{k}.")
        else:
            keys.append(f"{prefix}{k}")
    return keys


def leaves(v, path=()) -> list[tuple]:
    out = []
    if isinstance(v, dict):
        for k, x in v.items():
            out += leaves(x, path + (k,))
    elif isinstance(v, list) and v:
        # one element of each array (the first, the last), to keep the list short
        for i in sorted({0, len(v) - 1}):
            out += leaves(v[i], path + (i,))
    else:
        out.append(path)
    return out or [path]


def rows_of(path: Path) -> list[dict]:
    rows = list(csv.DictReader(io.StringIO(path.read_text())))
    for r in rows:
        r.pop("wall_s", None)
    return sorted(rows, key=lambda r: int(r["run"]))


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--shoal", default=str(ROOT / "target/release/shoal"))
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--inputs", type=int, default=1000, help="hostile inputs, at least")
    ap.add_argument("--kills", type=int, default=60, help="kills, about")
    ap.add_argument("--feasible", type=int, default=150,
                    help="random feasible missions that must plan and pass")
    ap.add_argument("--broken", type=int, default=115,
                    help="plans with one constraint broken that check must refuse")
    ap.add_argument("--work", default=None, help="scratch folder (default: a temporary one)")
    ap.add_argument("--json", default=None, help="also write the counts and examples here")
    a = ap.parse_args()
    work = Path(a.work) if a.work else Path(
        subprocess.check_output(["mktemp", "-d", "/tmp/shoal-reliability.XXXXXX"], text=True).strip())
    work.mkdir(parents=True, exist_ok=True)
    h = Harness(Path(a.shoal).resolve(), a.seed, work)
    start = time.monotonic()
    h.fixtures()
    n = a.inputs
    share = {  # fractions of the hostile inputs per class
        "set": 0.20, "scenario": 0.10, "check": 0.15, "simulate": 0.07, "view": 0.04,
        "export": 0.04, "plot": 0.03, "sim": 0.04, "studies": 0.08, "collect": 0.08,
        "compare": 0.03, "grids": 0.06, "waypoints": 0.04, "planted": 0.06,
    }
    m = {k: max(1, round(v * n)) for k, v in share.items()}
    m["set"] += max(0, n - sum(m.values()))
    h.feasible(a.feasible)
    h.broken(a.broken)
    h.set_overrides(m["set"])
    h.scenario_files(m["scenario"])
    for cmd in ["check", "simulate", "view", "export", "plot"]:
        h.plan_files(cmd, m[cmd])
    h.sim_files(m["sim"])
    h.studies(m["studies"])
    h.collects(m["collect"])
    h.compares(m["compare"])
    h.grids(m["grids"])
    h.waypoint_files(m["waypoints"])
    h.planted(m["planted"])
    h.kills_all(a.kills)
    table, ok = h.report()
    print(f"shoal reliability: seed {a.seed}, {h.shoal}, {time.monotonic() - start:.0f} s\n")
    print(table)
    if h.examples:
        print("\nfindings:")
        for e in h.examples[:40]:
            print(" ", json.dumps(e)[:400])
    if a.json:
        Path(a.json).write_text(json.dumps({
            "seed": a.seed, "inputs": {f"{c} / {k}": v for (c, k), v in h.table.items()},
            "kills": h.kills, "examples": h.examples}, indent=1))
    if not a.work:
        shutil.rmtree(work, ignore_errors=True)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
