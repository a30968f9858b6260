#!/bin/bash
# slurm_test.sh SOURCE_DIR BIN_DIR: starts a one-node Slurm cluster on localhost (munged,
# slurmctld, slurmd, all in a temp dir), runs contrib/slurm/verify.sbatch over 200
# captures in 7 shards, and checks the merged JUnit and summary against
# `decode verify --jobs 1` on the same list. Exit 77 (skipped) only when Slurm or munge
# is not installed; a daemon that does not start fails the test with its log.
set -u
src=$1 bin=$2
for tool in munged mungekey slurmctld slurmd sbatch sinfo scontrol; do
    command -v "$tool" >/dev/null || PATH=$PATH:/usr/sbin command -v "$tool" >/dev/null || {
        echo "SKIP: $tool is not installed (Debian packages slurm-wlm and munge)"
        exit 77
    }
done
export PATH=$PATH:/usr/sbin
tmp=$(mktemp -d /tmp/busdecode-slurm.XXXXXX)
chmod 755 "$tmp"  # munged wants its socket's directory reachable by all
pids=()
cleanup() {
    for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null; done
    for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null; done
    rm -rf "$tmp"
}
trap cleanup EXIT
fail() {
    echo "FAIL: $*"
    for log in "$tmp"/*.log; do echo "--- $log"; tail -n 20 "$log"; done
    exit 1
}

# Ports of our own, so that a Slurm already running here is left alone.
port=$((20000 + $$ % 20000))
mungekey -c -k "$tmp/munge.key" -b 1024 || fail "mungekey could not make a key"
chmod 400 "$tmp/munge.key"
munged -F --force --key-file="$tmp/munge.key" --socket="$tmp/munge.sock" \
    --pid-file="$tmp/munged.pid" --seed-file="$tmp/munge.seed" --log-file="$tmp/munged.log" >"$tmp/munged.out.log" 2>&1 &
pids+=($!)
mkdir -p "$tmp/state" "$tmp/spool"
cat >"$tmp/slurm.conf" <<CONF
ClusterName=busdecode-test
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=$(id -un)
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$tmp/munge.sock
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/slurmctld.log
SlurmdLogFile=$tmp/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
SchedulerType=sched/backfill
SchedulerParameters=sched_interval=1
MinJobAge=300
NodeName=localhost NodeAddr=127.0.0.1 CPUs=2 RealMemory=1000 State=UNKNOWN
PartitionName=test Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$tmp/slurm.conf
for i in $(seq 50); do [ -S "$tmp/munge.sock" ] && break; sleep 0.1; done
[ -S "$tmp/munge.sock" ] || fail "munged did not start"
slurmctld -D -i -f "$SLURM_CONF" >"$tmp/slurmctld.out.log" 2>&1 &
pids+=($!)
slurmd -D -N localhost -f "$SLURM_CONF" >"$tmp/slurmd.out.log" 2>&1 &
pids+=($!)
for i in $(seq 100); do
    state=$(sinfo -h -n localhost -o %t 2>/dev/null)
    [ "$state" = idle ] && break
    sleep 0.2
done
[ "$state" = idle ] || fail "the node is not idle after 20 s (sinfo: '$state')"

caps=$tmp/captures
bash "$src/tests/cluster/make_captures.sh" "$src" "$caps" 200 || fail "could not make captures"
rules=$src/captures/rules_bissc.toml
"$bin/decode" verify --from-list "$caps/list.txt" --rules "$rules" --opt bissc.bits=26 \
    --jobs 1 --junit "$tmp/single.xml" >"$tmp/single.txt" 2>/dev/null
[ -s "$tmp/single.xml" ] || fail "decode verify --jobs 1 wrote no JUnit"

start=$(date +%s%N)
DECODE=$bin/decode "$src/contrib/slurm/verify.sbatch" "$caps/list.txt" "$rules" "$tmp/out" 7 \
    --opt bissc.bits=26 || fail "verify.sbatch could not submit"
for i in $(seq 600); do [ -e "$tmp/out/merge.status" ] && break; sleep 0.2; done
[ -e "$tmp/out/merge.status" ] || fail "the merge job did not end within 120 s"
echo "slurm array of 7 shards over 200 captures: $((($(date +%s%N) - start) / 1000000)) ms"

# One unreadable capture in the list: the single run and the merge both exit 2.
[ "$(cat "$tmp/out/merge.status")" = 2 ] || fail "merge exit $(cat "$tmp/out/merge.status"), not 2"
[ "$(tail -n 1 "$tmp/single.txt")" = "$(cat "$tmp/out/summary.txt")" ] ||
    fail "summaries differ: '$(tail -n 1 "$tmp/single.txt")' / '$(cat "$tmp/out/summary.txt")'"
python3 "$src/tests/cluster/junit_cases.py" "$tmp/single.xml" "$tmp/out/all.xml" ||
    fail "merged JUnit testcases differ from --jobs 1"
[ "$(ls "$tmp/out"/shard-*.xml | wc -l)" = 7 ] || fail "not 7 shard files"
echo "PASS: merged JUnit of 7 Slurm tasks equals decode verify --jobs 1"

# A task killed by a signal (shard 3/7 here): its captures, and only those, are errors.
cat >"$tmp/decode-killed-on-3" <<WRAP
#!/bin/bash
case " \$* " in *" --shard 3/7 "*) kill -KILL \$\$ ;; esac
exec "$bin/decode" "\$@"
WRAP
chmod +x "$tmp/decode-killed-on-3"
DECODE=$tmp/decode-killed-on-3 "$src/contrib/slurm/verify.sbatch" "$caps/list.txt" "$rules" \
    "$tmp/killed" 7 --opt bissc.bits=26 || fail "verify.sbatch could not submit"
for i in $(seq 600); do [ -e "$tmp/killed/merge.status" ] && break; sleep 0.2; done
[ -e "$tmp/killed/merge.status" ] || fail "the merge job did not end within 120 s"
[ "$(cat "$tmp/killed/merge.status")" = 2 ] || fail "merge after a killed task did not exit 2"
python3 - "$caps/list.txt" "$tmp/killed/all.xml" <<'PY' || fail "the killed shard's errors are wrong"
import pathlib, re, sys, xml.etree.ElementTree as ET
# JUnit classes are "busdecode.<stem>" (the stems here are unique).
captures = ["busdecode." + re.sub(r"[^A-Za-z0-9_-]", "_", pathlib.Path(l.strip()).stem)
            for l in open(sys.argv[1]) if l.strip()]
cases = list(ET.parse(sys.argv[2]).getroot().iter("testcase"))
errors = [c.get("classname") for c in cases if c.find("error") is not None and c.find("error").get("type") == "shard"]
n = len(captures)
assert errors == captures[n * 2 // 7:n * 3 // 7], errors
assert len({c.get("classname") for c in cases}) == n
PY
echo "PASS: a killed task's captures are errors in the merged JUnit, and the merge exits 2"

# A list of relative paths, submitted from where they hold: the tasks see the same files.
sed "s|^$caps/||" "$caps/list.txt" | head -n 20 >"$caps/relative.txt"
(cd "$caps" && DECODE=$bin/decode "$src/contrib/slurm/verify.sbatch" relative.txt "$rules" \
    "$tmp/relative" 2 --opt bissc.bits=26) || fail "verify.sbatch could not submit"
for i in $(seq 600); do [ -e "$tmp/relative/merge.status" ] && break; sleep 0.2; done
[ -e "$tmp/relative/merge.status" ] || fail "the merge job did not end within 120 s"
single=$(cd "$caps" && "$bin/decode" verify --from-list relative.txt --rules "$rules" \
    --opt bissc.bits=26 2>/dev/null | tail -n 1)
[ "$single" = "$(cat "$tmp/relative/summary.txt")" ] ||
    fail "relative paths: '$single' / '$(cat "$tmp/relative/summary.txt")'"
echo "PASS: the tasks resolve a list's relative paths where it was submitted"
