#!/usr/bin/env python3
"""scripts/cluster/{sweep,suite,render}-job.yaml (the one given) tells the truth (no Kubernetes here, so
the file itself is checked): the shard Job's completions, parallelism and SHARDS agree, the merge lists
the same shards with the same sweep or suite flags (a render's merge takes none: it checks that the
shards agree), each shard writes its own folder under the one the merge reads, and --threads follows
the pod's CPU limit through the downward API."""
import sys
import yaml

docs = [d for d in yaml.safe_load_all(open(sys.argv[1])) if d]
jobs = {d["metadata"]["name"]: d for d in docs if d["kind"] == "Job"}
kind = next(k for k in ("suite", "sweep", "render") if f"hoilcd-{k}-shards" in jobs)
shard, merge = jobs[f"hoilcd-{kind}-shards"], jobs[f"hoilcd-{kind}-merge"]


def container(job):
    return job["spec"]["template"]["spec"]["containers"][0]


def env(job, name):
    return next(e for e in container(job)["env"] if e["name"] == name)


def fail(message):
    sys.exit("FAIL: " + message)


shards = int(env(shard, "SHARDS")["value"])
spec = shard["spec"]
if spec["completionMode"] != "Indexed":
    fail("the shard Job must be Indexed (JOB_COMPLETION_INDEX names the shard)")
if not spec["completions"] == spec["parallelism"] == shards == int(env(merge, "SHARDS")["value"]):
    fail(f"completions {spec['completions']}, parallelism {spec['parallelism']} and SHARDS disagree")
cpus = env(shard, "CPUS")["valueFrom"]["resourceFieldRef"]
if cpus["resource"] != "limits.cpu":
    fail("CPUS must come from the pod's CPU limit")
resources = container(shard)["resources"]
if resources["requests"] != resources["limits"]:
    fail("requests and limits differ: the pod could get fewer cores than --threads")
shard_args, merge_args = container(shard)["args"][0], container(merge)["args"][0]
if '--threads "$CPUS"' not in shard_args:
    fail("--threads is not $CPUS: " + shard_args)


def command_flags(args):
    words = args.split()
    start = words.index(kind)
    end = next(i for i, w in enumerate(words) if w in ("--shard", "--merge"))
    return words[start:end]


if kind == "render":
    if " merge " not in f" {merge_args} " or "--shard" not in shard_args:
        fail("the render's shards must run render --shard and its merge hoilcd merge: " + merge_args)
elif command_flags(shard_args) != command_flags(merge_args):
    fail(f"shard and merge {kind} different things: {command_flags(shard_args)} vs {command_flags(merge_args)}")
words = merge_args.split()
out = words[words.index("-o") + 1]
if kind == "render":  # the dataset goes beside the shards, into a folder of its own
    out = out.rsplit("/", 1)[0]
if f'-o "{out}/shard-$JOB_COMPLETION_INDEX"' not in shard_args or f"{out}/shard-$i" not in merge_args:
    fail(f"the shards do not write the folders the merge into {out} reads: {shard_args} / {merge_args}")
print(f"{kind}-job.yaml: consistent")
