#!/usr/bin/env python3
"""scripts/cluster/k8s-job.sh KIND (the kind given) renders scripts/cluster/KIND-job.yaml.in into a
manifest that tells the truth (no Kubernetes here, so the manifest itself is checked), with the
defaults and with every parameter set: the shard Job's completions, parallelism and SHARDS agree, the
merge lists the same shards with the same sweep or suite flags (a render's merge takes none: it checks
that the shards agree), each shard writes its own folder under OUT, which the merge reads, --threads
follows the pod's CPU limit through the downward API, the shard and merge pods get the cores and
memory asked for, and no placeholder is left. A bad parameter is refused by name, printing nothing."""
import os
import subprocess
import sys
import yaml

renderer, kind = sys.argv[1], sys.argv[2]
PARAMETERS = ("IMAGE", "SHARDS", "CPUS", "MEM", "MERGE_CPUS", "MERGE_MEM", "STORAGE", "OUT", "METHODS", "FRAMES",
              "SWEEP", "VALUES", "SCENE", "SEEDS", "SUITE", "SPLIT", "SEED", "OUTPUTS", "SET")


def fail(message):
    sys.exit(f"FAIL ({kind}): {message}")


def render(settings):
    env = {k: v for k, v in os.environ.items() if k not in PARAMETERS}
    env.update(settings)
    return subprocess.run(["bash", renderer, kind], env=env, capture_output=True, text=True)


def container(job):
    return job["spec"]["template"]["spec"]["containers"][0]


def env(job, name):
    return next(e for e in container(job)["env"] if e["name"] == name)


def check(settings, expect):
    result = render(settings)
    if result.returncode != 0:
        fail(f"{settings} was refused: {result.stderr}")
    if "${" in result.stdout.replace("${...}", ""):
        fail(f"a placeholder is left in the manifest of {settings}")
    docs = [d for d in yaml.safe_load_all(result.stdout) if d]
    jobs = {d["metadata"]["name"]: d for d in docs if d["kind"] == "Job"}
    claim = next(d for d in docs if d["kind"] == "PersistentVolumeClaim")
    shard, merge = jobs[f"hoilcd-{kind}-shards"], jobs[f"hoilcd-{kind}-merge"]

    shards = int(env(shard, "SHARDS")["value"])
    spec = shard["spec"]
    if spec["completionMode"] != "Indexed":
        fail("the shard Job must be Indexed (JOB_COMPLETION_INDEX names the shard)")
    if not spec["completions"] == spec["parallelism"] == shards == int(env(merge, "SHARDS")["value"]) == expect["shards"]:
        fail(f"completions {spec['completions']}, parallelism {spec['parallelism']} and SHARDS disagree "
             f"with {expect['shards']}")
    if env(shard, "CPUS")["valueFrom"]["resourceFieldRef"]["resource"] != "limits.cpu":
        fail("CPUS must come from the pod's CPU limit")
    for job, cpu, memory in ((shard, expect["cpu"], expect["memory"]), (merge, expect["merge_cpu"], expect["merge_memory"])):
        resources = container(job)["resources"]
        if resources["requests"] != resources["limits"]:
            fail("requests and limits differ: the pod could get fewer cores than --threads")
        if resources["limits"] != {"cpu": cpu, "memory": memory}:
            fail(f"{job['metadata']['name']} asks {resources['limits']}, not {cpu} cores and {memory}")
        if container(job)["image"] != expect["image"]:
            fail(f"{job['metadata']['name']} runs {container(job)['image']}, not {expect['image']}")
    if claim["spec"]["resources"]["requests"]["storage"] != expect["storage"]:
        fail(f"the volume asks {claim['spec']['resources']['requests']['storage']}, not {expect['storage']}")
    shard_args, merge_args = container(shard)["args"][0], container(merge)["args"][0]
    if '--threads "$CPUS"' not in shard_args:
        fail("--threads is not $CPUS: " + shard_args)
    if expect["command"] not in " ".join(shard_args.split()):
        fail(f"the shards do not run {expect['command']}: {shard_args}")

    def command_flags(args):
        words = args.split()
        start = words.index(kind)
        end = next(i for i, w in enumerate(words) if w in ("--shard", "--merge"))
        return words[start:end]

    if kind == "render":
        if " merge " not in f" {merge_args} " or "--shard" not in shard_args:
            fail("the render's shards must run render --shard and its merge hoilcd merge: " + merge_args)
        if '--threads "$CPUS"' not in merge_args or env(merge, "CPUS")["valueFrom"]["resourceFieldRef"]["resource"] != "limits.cpu":
            fail("the render's merge does not pass its pod's CPU limit to --threads: " + merge_args)
    elif command_flags(shard_args) != command_flags(merge_args):
        fail(f"shard and merge {kind} different things: {command_flags(shard_args)} vs {command_flags(merge_args)}")
    words = merge_args.split()
    out = words[words.index("-o") + 1]
    if kind == "render":  # the dataset goes beside the shards, into a folder of its own
        out = out.rsplit("/", 1)[0]
    if out != expect["out"]:
        fail(f"the merge writes into {out}, not OUT={expect['out']}")
    if f'-o "{out}/shard-$JOB_COMPLETION_INDEX"' not in shard_args or f"{out}/shard-$i" not in merge_args:
        fail(f"the shards do not write the folders the merge into {out} reads: {shard_args} / {merge_args}")


defaults = {
    "sweep": {"shards": 7, "memory": "6Gi", "storage": "50Gi", "out": "/sweeps/crowd",
              "command": "sweep scenes/crowded_room.json --set crowd.people_per_table=0,1,2,3,4,5,6 --seeds 3 --methods paper"},
    "suite": {"shards": 13, "memory": "6Gi", "storage": "100Gi", "out": "/suites/standard",
              "command": "suite suites/standard.json --split all --methods paper"},
    "render": {"shards": 4, "memory": "4Gi", "storage": "20Gi", "out": "/renders/paper_room",
               "command": "render scenes/paper_room.json --shard"},
}[kind]
check({}, dict(defaults, cpu="4", merge_cpu="1", merge_memory="2Gi", image="hoilcd:latest"))

mount = defaults["out"].rsplit("/", 1)[0]
settings = {"IMAGE": "registry.example/hoilcd:1.0", "SHARDS": "5", "CPUS": "2", "MEM": "3Gi", "MERGE_CPUS": "2",
            "MERGE_MEM": "1500Mi", "STORAGE": "10Gi", "OUT": f"{mount}/mine"}
settings.update({
    "sweep": {"SWEEP": "occlusion", "VALUES": "0,4", "SEEDS": "2", "METHODS": "slcd,dlcd", "FRAMES": "1300"},
    "suite": {"SUITE": "suites/ci.json", "SPLIT": "test", "METHODS": "slcd,dlcd"},
    "render": {"SCENE": "scenes/crowded_room.json", "FRAMES": "300", "SEED": "7", "OUTPUTS": "thermal",
               "SET": "crowd.walkers=4 camera.video.enabled=true"},
}[kind])
command = {
    "sweep": "sweep scenes/paper_room.json --set crowd.walkers=0,4 --seeds 2 --methods slcd,dlcd --set frames=1300",
    "suite": "suite suites/ci.json --split test --methods slcd,dlcd",
    "render": "render scenes/crowded_room.json --frames 300 --seed 7 --outputs thermal --set crowd.walkers=4 "
              "--set camera.video.enabled=true --shard",
}[kind]
check(settings, {"shards": 5, "cpu": "2", "memory": "3Gi", "merge_cpu": "2", "merge_memory": "1500Mi",
                 "storage": "10Gi", "out": f"{mount}/mine", "image": "registry.example/hoilcd:1.0", "command": command})

refused = [({"SHARDS": "0"}, "SHARDS must be a positive whole number, not '0'"),
           ({"CPUS": "1.5"}, "CPUS must be a positive whole number, not '1.5'"),
           ({"MERGE_CPUS": "x"}, "MERGE_CPUS must be a positive whole number, not 'x'"),
           ({"MEM": "6GB"}, "MEM must be a Kubernetes quantity like 6Gi or 6000Mi, not '6GB'"),
           ({"MERGE_MEM": "-1Gi"}, "MERGE_MEM must be a Kubernetes quantity"),
           ({"STORAGE": "lots"}, "STORAGE must be a Kubernetes quantity"),
           ({"IMAGE": "my image"}, "IMAGE must be an image reference"),
           ({"OUT": "/elsewhere/x"}, f"OUT must be a folder on the shared volume, under {mount}/"),
           ({"OUT": f"{mount}/../x"}, "OUT must be a folder on the shared volume")]
refused += {"sweep": [({"SWEEP": "both"}, "SWEEP must be crowd or occlusion, not 'both'"),
                      ({"SEEDS": "0"}, "SEEDS must be a positive whole number"),
                      ({"VALUES": "0, 2"}, "VALUES may hold only"),
                      ({"METHODS": "slcd;rm"}, "METHODS may hold only letters, digits")],
            "suite": [({"SPLIT": "train"}, "SPLIT must be dev, test or all, not 'train'"),
                      ({"SUITE": "my suite.json"}, "SUITE may hold only"),
                      ({"METHODS": "slcd;rm"}, "METHODS may hold only letters, digits")],
            "render": [({"SET": "crowd.walkers"}, "SET: each override must look like KEY=VALUE, not 'crowd.walkers'"),
                       ({"SET": "a=$(id)"}, "SET: 'a=$(id)' may hold only"),
                       ({"FRAMES": "many"}, "FRAMES must be a positive whole number")]}[kind]
for bad, message in refused:
    result = render(bad)
    if result.returncode == 0 or result.stdout or message not in result.stderr:
        fail(f"{bad} not refused with \"{message}\": exit {result.returncode}, {result.stderr!r}")
if render({}).returncode != 0 or subprocess.run(["bash", renderer, "nothing"], capture_output=True).returncode != 2:
    fail("an unknown kind is not refused")
print(f"{kind}: the manifest is consistent with the defaults and with every parameter set; bad parameters refused")
