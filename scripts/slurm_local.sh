#!/usr/bin/env bash
# Prove `snakemake --profile profiles/cluster` on a single-node SLURM started here.
#
#   sudo bash scripts/slurm_local.sh            # as root, on a Debian (bookworm) machine or container
#
# 1. installs slurm-wlm, slurmdbd, munge and mariadb-server with apt when missing;
# 2. writes its own munge key, slurm.conf and slurmdbd.conf into a temporary
#    directory (nothing under /etc or in the repository) and starts munged,
#    mariadbd, slurmdbd, slurmctld and slurmd in the background, on ports of
#    their own, with accounting (sacct, which the executor plugin polls), and
#    an srun wrapper for the jobs (write_slurm_conf says why);
# 3. waits until `sinfo` shows the node idle;
# 4. copies the repository's files (tracked and untracked, not ignored) twice
#    and builds the rest study and the two-block system sweep (both in chunks)
#    in one copy through the profile on SLURM and in the other with
#    `snakemake --cores 2`;
# 5. prints the SLURM jobs (sacct), both wall times and compares the two
#    results/studies/rest.csv and results/sweeps/two_blocks.csv byte for byte
#    (exit status 1 if they differ);
# 6. stops every daemon it started and removes the directory, also on error
#    or Ctrl-C (set LUMPED_SLURM_KEEP=1 to keep the directory and its logs).
#
# Needs the repository's environment active (snakemake and the executor
# plugin from environment-pip.txt).  Every wait is bounded; a failure ends
# with one line "slurm_local: ..." (after the end of snakemake's log if a
# build failed) and exit status 2.  CI does not run it.
set -euo pipefail

REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
readonly REPO
readonly TARGETS=("results/studies/rest.csv" "results/sweeps/two_blocks.csv")
readonly PACKAGES=(slurm-wlm slurmdbd munge mariadb-server)
readonly WAIT_DAEMON=60     # s, for each daemon to answer
readonly WAIT_RUN=900       # s, for each snakemake run
readonly CLUSTER=lumpedlocal ACCOUNT=lumped PARTITION=debug
readonly PORT_CTLD=16817 PORT_SLURMD=16818 PORT_DBD=16819 PORT_SQL=16306
WORK=""
PIDS=()
SLURM_UP=0 # 1 once slurmctld is started: jobs may need cancelling

die() {
    echo "slurm_local: $*" >&2
    exit 2
}

usage() {
    sed -n '2,26p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'
}

# wait_for SECONDS WHAT COMMAND...: retry COMMAND every second until it succeeds.
wait_for() {
    local seconds=$1 what=$2
    shift 2
    for ((i = 0; i < seconds; i++)); do
        "$@" > /dev/null 2>&1 && return 0
        sleep 1
    done
    die "$what did not happen within ${seconds} s (logs in ${WORK}/log; LUMPED_SLURM_KEEP=1 keeps them)"
}

munge_answers() {
    munge -S "$WORK/munge/munge.socket" -n | unmunge -S "$WORK/munge/munge.socket"
}

node_idle() {
    [[ $(sinfo --noheader -o %t) == idle ]]
}

port_free() {
    ! (exec 3<> "/dev/tcp/127.0.0.1/$1") 2> /dev/null
}

check_machine() {
    [[ $(id -u) -eq 0 ]] || die "must run as root (it installs packages and starts daemons)"
    command -v snakemake > /dev/null || die "snakemake not found: activate the repository's environment first"
    python -c "import snakemake_executor_plugin_slurm" 2> /dev/null ||
        die "snakemake-executor-plugin-slurm not installed: pip install -r environment-pip.txt"
    command -v git > /dev/null || die "git not found (used to list the repository's files)"
    for port in $PORT_CTLD $PORT_SLURMD $PORT_DBD $PORT_SQL; do
        port_free "$port" || die "port $port is in use (another SLURM or database here?)"
    done
}

install_packages() {
    local missing=()
    for p in "${PACKAGES[@]}"; do
        dpkg-query -W -f '${Status}' "$p" 2> /dev/null | grep -q "install ok installed" || missing+=("$p")
    done
    if ((${#missing[@]})); then
        command -v apt-get > /dev/null || die "missing ${missing[*]} and no apt-get to install them"
        echo "== installing ${missing[*]}"
        apt-get update -q > "$WORK/log/apt.log" 2>&1 || die "apt-get update failed (see $WORK/log/apt.log)"
        DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}" \
            >> "$WORK/log/apt.log" 2>&1 || die "apt-get install ${missing[*]} failed (see $WORK/log/apt.log)"
    fi
    echo "== Debian packages: $(dpkg-query -W -f '${Package} ${Version}\n' "${PACKAGES[@]}" | paste -sd, | sed 's/,/, /g')"
}

# start NAME COMMAND...: run a daemon in the foreground of a background job, remember its pid.
# It gets a session of its own, so that Ctrl-C reaches snakemake (which then
# cancels its SLURM jobs) but not the daemons it needs for that; stop_all
# stops them afterwards.
start() {
    local name=$1
    shift
    setsid "$@" > "$WORK/log/$name.out" 2>&1 &
    PIDS+=($!)
}

stop_all() {
    local status=$?
    set +e
    if ((SLURM_UP)); then
        timeout 20 scancel --quiet --user root 2> /dev/null
    fi
    for ((i = ${#PIDS[@]} - 1; i >= 0; i--)); do # the reverse of the start order
        kill "${PIDS[i]}" 2> /dev/null
        for ((t = 0; t < 20; t++)); do
            kill -0 "${PIDS[i]}" 2> /dev/null || break
            sleep 0.5
        done
        kill -9 "${PIDS[i]}" 2> /dev/null
        wait "${PIDS[i]}" 2> /dev/null
    done
    if [[ -n $WORK && -d $WORK ]]; then
        if [[ ${LUMPED_SLURM_KEEP:-0} == 1 ]]; then
            echo "== kept $WORK"
        else
            rm -rf "$WORK"
        fi
    fi
    ((${#PIDS[@]})) && echo "== stopped ${#PIDS[@]} daemons"
    exit "$status"
}

write_munge() {
    mkdir -p "$WORK/munge"
    chmod 711 "$WORK/munge" # the socket must be reachable, the key stays 400
    dd if=/dev/urandom of="$WORK/munge/munge.key" bs=1024 count=1 status=none
    chmod 400 "$WORK/munge/munge.key"
}

start_munge() {
    start munged munged --foreground --force --key-file="$WORK/munge/munge.key" \
        --socket="$WORK/munge/munge.socket" --pid-file="$WORK/munge/munged.pid" \
        --log-file="$WORK/log/munged.log" --seed-file="$WORK/munge/munged.seed"
    wait_for "$WAIT_DAEMON" "munged answering" munge_answers
}

start_database() {
    mariadb-install-db --no-defaults --user=root --datadir="$WORK/mysql" --auth-root-authentication-method=socket \
        > "$WORK/log/mariadb-install.log" 2>&1 || die "mariadb-install-db failed (see $WORK/log/mariadb-install.log)"
    start mariadbd mariadbd --no-defaults --user=root --datadir="$WORK/mysql" --socket="$WORK/mysql.sock" \
        --port="$PORT_SQL" --bind-address=127.0.0.1 --pid-file="$WORK/mysql.pid" \
        --log-error="$WORK/log/mariadb.log" --innodb-lock-wait-timeout=900
    wait_for "$WAIT_DAEMON" "mariadbd answering" mariadb --no-defaults -S "$WORK/mysql.sock" -u root -e "select 1"
    DB_PASS=$(head -c 12 /dev/urandom | od -An -tx1 | tr -d ' \n')
    mariadb --no-defaults -S "$WORK/mysql.sock" -u root -e "
        CREATE USER 'slurm'@'127.0.0.1' IDENTIFIED BY '$DB_PASS';
        GRANT ALL ON slurm_acct_db.* TO 'slurm'@'127.0.0.1';" || die "could not create the database user"
}

write_slurm_conf() {
    local host mem
    host=$(hostname -s)
    mem=$(awk '/MemTotal/ {print int($2 / 1024 * 0.8)}' /proc/meminfo) # MB: below what slurmd measures
    mkdir -p "$WORK/etc" "$WORK/state" "$WORK/spool"
    cat > "$WORK/etc/slurm.conf" << EOF
ClusterName=$CLUSTER
SlurmctldHost=$host
SlurmUser=root
SlurmctldPort=$PORT_CTLD
SlurmdPort=$PORT_SLURMD
AuthType=auth/munge
AuthInfo=socket=$WORK/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$WORK/state
SlurmdSpoolDir=$WORK/spool
SlurmctldPidFile=$WORK/slurmctld.pid
SlurmdPidFile=$WORK/slurmd.pid
SlurmctldLogFile=$WORK/log/slurmctld.log
SlurmdLogFile=$WORK/log/slurmd.log
# a container: no cgroups, no systemd
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
# accounting through slurmdbd: sacct answers the plugin's status queries
AccountingStorageType=accounting_storage/slurmdbd
AccountingStorageHost=localhost
AccountingStoragePort=$PORT_DBD
# the munge socket for talking to slurmdbd (AuthInfo does not cover it)
AccountingStoragePass=$WORK/munge/munge.socket
AccountingStorageEnforce=associations
AccountingStoreFlags=job_comment
ReturnToService=2
NodeName=$host CPUs=$(nproc) RealMemory=$mem State=UNKNOWN
PartitionName=$PARTITION Nodes=$host Default=YES MaxTime=60 State=UP
EOF
    cat > "$WORK/etc/slurmdbd.conf" << EOF
AuthType=auth/munge
AuthInfo=socket=$WORK/munge/munge.socket
DbdHost=localhost
DbdPort=$PORT_DBD
SlurmUser=root
PidFile=$WORK/slurmdbd.pid
LogFile=$WORK/log/slurmdbd.log
StorageType=accounting_storage/mysql
StorageHost=127.0.0.1
StoragePort=$PORT_SQL
StorageUser=slurm
StoragePass=$DB_PASS
StorageLoc=slurm_acct_db
EOF
    chmod 600 "$WORK/etc/slurmdbd.conf"
    export SLURM_CONF="$WORK/etc/slurm.conf"
    # Inside a job the plugin runs the rule through `srun` with every SLURM_*
    # variable but a few removed, SLURM_CONF among them; a real cluster's
    # slurm.conf sits where srun looks by default, this one does not.  So the
    # jobs find `srun` first in $WORK/bin, a wrapper that gives it SLURM_CONF.
    mkdir -p "$WORK/bin"
    printf '#!/bin/sh\nSLURM_CONF=%s exec %s "$@"\n' "$SLURM_CONF" "$(command -v srun)" > "$WORK/bin/srun"
    chmod 755 "$WORK/bin/srun"
    export PATH="$WORK/bin:$PATH"
}

start_slurm() {
    start slurmdbd slurmdbd -D
    wait_for "$WAIT_DAEMON" "slurmdbd answering" sacctmgr --noheader list cluster
    sacctmgr -i add cluster "$CLUSTER" > "$WORK/log/sacctmgr.log" 2>&1
    sacctmgr -i add account "$ACCOUNT" Cluster="$CLUSTER" Description=lumped Organization=lumped \
        >> "$WORK/log/sacctmgr.log" 2>&1
    sacctmgr -i add user root Account="$ACCOUNT" Cluster="$CLUSTER" >> "$WORK/log/sacctmgr.log" 2>&1 ||
        die "sacctmgr could not register account $ACCOUNT (see $WORK/log/sacctmgr.log)"
    start slurmctld slurmctld -D
    SLURM_UP=1
    start slurmd slurmd -D
    wait_for "$WAIT_DAEMON" "the node becoming idle in sinfo" node_idle
    sinfo
}

copy_repository() {
    local dest=$1
    mkdir -p "$dest"
    (cd "$REPO" && git ls-files -z --cached --others --exclude-standard |
        while IFS= read -r -d '' f; do [[ -e $f ]] && printf '%s\0' "$f"; done | tar --null -T - -cf -) |
        tar -C "$dest" -xf - || die "could not copy the repository into $dest"
}

# run_study DIR LABEL ARGS...: build TARGETS in DIR with snakemake ARGS; print
# snakemake's lines that name SLURM job ids and its summary, then the wall time.
run_study() {
    local dir=$1 label=$2 log="$WORK/log/snakemake-$2.log" start end
    shift 2
    start=$(date +%s.%N)
    if ! (cd "$dir" && timeout "$WAIT_RUN" snakemake "$@" "${TARGETS[@]}") > "$log" 2>&1; then
        tail -n 40 "$log" >&2
        die "snakemake ($label) failed or took over ${WAIT_RUN} s (the end of its log is above)"
    fi
    end=$(date +%s.%N)
    grep -E "^Using profile|submitted with SLURM jobid|^Job stats|^(job|total|study_rest[a-z_]*|sweep_system[a-z_]*) +[0-9a-z]|steps \(100%\) done" "$log" |
        sed -e "s|$WORK/||g" -e 's/^/  /'
    awk -v label="$label" -v s="$start" -v e="$end" 'BEGIN {printf "== %s: wall time %.1f s\n", label, e - s}'
}

main() {
    case ${1:-} in
        "") ;;
        -h | --help)
            usage
            exit 0
            ;;
        *) die "unknown argument '$1' (no arguments; --help says what it does)" ;;
    esac
    check_machine
    WORK=$(mktemp -d /tmp/lumped-slurm.XXXXXX)
    mkdir -p "$WORK/log"
    trap stop_all EXIT
    trap 'echo "slurm_local: interrupted" >&2; exit 130' INT TERM
    install_packages
    write_munge
    start_munge
    start_database
    write_slurm_conf
    start_slurm
    copy_repository "$WORK/on-slurm"
    copy_repository "$WORK/local"
    local since
    since=$(date +%Y-%m-%dT%H:%M:%S)
    echo "== the rest study and the system sweep through profiles/cluster (account $ACCOUNT, partition $PARTITION)"
    LUMPED_SLURM_ACCOUNT=$ACCOUNT LUMPED_SLURM_PARTITION=$PARTITION run_study "$WORK/on-slurm" slurm \
        --profile profiles/cluster --slurm-init-seconds-before-status-checks 2
    echo "== the SLURM jobs (sacct)"
    sacct -X --starttime "$since" --format=JobID,Comment%40,Partition,Account,State,ExitCode,Elapsed,NodeList
    echo "== the same built here (snakemake --cores 2)"
    run_study "$WORK/local" local --cores 2
    local target
    for target in "${TARGETS[@]}"; do
        echo "== $target, SLURM against local"
        sha256sum "$WORK/on-slurm/$target" "$WORK/local/$target" | sed "s|$WORK/||"
        if cmp "$WORK/on-slurm/$target" "$WORK/local/$target"; then
            echo "== identical, byte for byte ($(wc -l < "$WORK/local/$target") lines)"
        else
            echo "== the two files DIFFER" >&2
            exit 1
        fi
    done
}

main "$@"
