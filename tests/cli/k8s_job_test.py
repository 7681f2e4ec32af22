#!/usr/bin/env python3
"""scripts/cluster/sweep-job.yaml tells the truth (no Kubernetes here, so the file itself is checked):
the shard Job's completions, parallelism and SHARDS agree, the merge lists the same shards with the
same sweep flags, and --threads follows the pod's CPU limit through the downward API."""
import sys
import yaml

docs = [d for d in yaml.safe_load_all(open(sys.argv[1])) if d]
jobs = {d["metadata"]["name"]: d for d in docs if d["kind"] == "Job"}
shard, merge = jobs["hoilcd-sweep-shards"], jobs["hoilcd-sweep-merge"]


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


def sweep_flags(args):
    words = args.split()
    start = words.index("sweep")
    end = next(i for i, w in enumerate(words) if w in ("--shard", "--merge"))
    return words[start:end]


if sweep_flags(shard_args) != sweep_flags(merge_args):
    fail(f"shard and merge sweep different things: {sweep_flags(shard_args)} vs {sweep_flags(merge_args)}")
print("sweep-job.yaml: consistent")
