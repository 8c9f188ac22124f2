"""A local stand-in for SLURM's `sbatch` and `squeue`, as the tests put
them on PATH: `sbatch [--parsable] [OPTIONS] SCRIPT` reads the script's
`#SBATCH` directives (the command line's options override them) for
`--array=FIRST-LAST[%LIMIT]` and `--output=PATTERN` (%A the job, %a the
array index), prints the job's id and starts a controller in its own
session, which runs the array's tasks as `bash SCRIPT` (at most LIMIT at
once) with SLURM_ARRAY_JOB_ID, SLURM_ARRAY_TASK_ID and SLURM_JOB_ID set,
each one's output in its file, as slurmctld and slurmd would. `squeue -h
-j JOB -o FORMAT` prints a line while the job has tasks pending or
running, nothing once it has ended, and fails for a job it never knew.

The state lives in $FAKE_SLURM_DIR. $FAKE_SLURM_FAIL (indices, comma
separated) are tasks whose node "fails": they end without running the
script. $FAKE_SLURM_HOLD: the controller waits for that file before
running anything (a job queued behind others)."""
from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import time
from pathlib import Path


def install(bin_dir: Path) -> Path:
    """sbatch and squeue in bin_dir, running this file with this Python."""
    bin_dir.mkdir(parents=True, exist_ok=True)
    for tool in ("sbatch", "squeue"):
        path = bin_dir / tool
        path.write_text(f"#!{sys.executable}\nimport sys\nsys.path.insert(0, {str(Path(__file__).parent)!r})\n"
                        f"import fake_slurm\nsys.exit(fake_slurm.main({tool!r}, sys.argv[1:]))\n")
        path.chmod(0o755)
    return bin_dir


def _state() -> Path:
    return Path(os.environ["FAKE_SLURM_DIR"])


def sbatch(args: list) -> int:
    if not args:
        print("sbatch: error: no script", file=sys.stderr)
        return 1
    script = Path(args[-1])
    options = [a for a in args[:-1] if a != "--parsable"]
    directives = re.findall(r"^#SBATCH\s+(\S+)", script.read_text(), re.M)
    settings = {}
    for d in directives + options:
        name, _, value = d.partition("=")
        settings[name] = value
    m = re.fullmatch(r"(\d+)-(\d+)(?:%(\d+))?", settings.get("--array", "0-0"))
    if m is None:
        print(f"sbatch: error: invalid --array {settings.get('--array')}", file=sys.stderr)
        return 1
    state = _state()
    state.mkdir(parents=True, exist_ok=True)
    counter = state / "next_id"
    job = int(counter.read_text()) if counter.is_file() else 1000
    counter.write_text(str(job + 1))
    (state / f"{job}.json").write_text(json.dumps({"args": args, "settings": settings}))
    (state / f"{job}.running").write_text("")
    subprocess.Popen([sys.executable, __file__, "controller", str(job), str(script),
                      m.group(1), m.group(2), m.group(3) or "0",
                      settings.get("--output", "slurm-%A_%a.out")],
                     start_new_session=True, stdin=subprocess.DEVNULL,
                     stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    print(job if "--parsable" in args else f"Submitted batch job {job}")
    return 0


def controller(job: str, script: str, first: str, last: str, limit: str, output: str) -> int:
    state = _state()
    hold = os.environ.get("FAKE_SLURM_HOLD")
    while hold and not Path(hold).exists():
        time.sleep(0.05)
    fail = {int(i) for i in os.environ.get("FAKE_SLURM_FAIL", "").split(",") if i}
    todo = list(range(int(first), int(last) + 1))
    at_once = int(limit) or 2
    running = []
    while todo or running:
        running = [p for p in running if p.poll() is None]
        while todo and len(running) < at_once:
            i = todo.pop(0)
            log = Path(output.replace("%A", job).replace("%a", str(i)))
            log.parent.mkdir(parents=True, exist_ok=True)
            if i in fail:
                log.write_text("slurmstepd: error: *** JOB CANCELLED DUE TO NODE FAILURE ***\n")
                continue
            env = dict(os.environ, SLURM_ARRAY_JOB_ID=job, SLURM_ARRAY_TASK_ID=str(i),
                       SLURM_JOB_ID=f"{job}{i}")
            with open(log, "w") as out:
                running.append(subprocess.Popen(["bash", script], env=env, stdout=out,
                                                stderr=subprocess.STDOUT))
        time.sleep(0.02)
    (state / f"{job}.running").unlink()
    (state / f"{job}.done").write_text("")
    return 0


def squeue(args: list) -> int:
    job = args[args.index("-j") + 1] if "-j" in args else None
    state = _state()
    if job is None or not (state / f"{job}.json").is_file():
        print("slurm_load_jobs error: Invalid job id specified", file=sys.stderr)
        return 1
    if (state / f"{job}.running").is_file():
        if "-h" not in args:
            print("JOBID ST")
        print(f"{job}_[0-?] R")
    return 0


def main(tool: str, args: list) -> int:
    if tool == "sbatch":
        return sbatch(args)
    if tool == "squeue":
        return squeue(args)
    return controller(*args)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2:]))
