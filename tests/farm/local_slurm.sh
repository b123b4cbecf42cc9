#!/usr/bin/env bash
# Starts or stops a one-node Slurm cluster on this machine, as root, from tests/farm/slurm.conf.in:
#   local_slurm.sh start DIR   munged (as the munge user, own key and socket), slurmctld and slurmd,
#                              state, spool, pid and log files all in DIR; waits until the node
#                              is idle and prints `export SLURM_CONF=DIR/slurm.conf`
#   local_slurm.sh stop DIR    ends the three daemons by the pids they wrote into DIR
# No systemd needed. Exits 77 (skip) where Slurm or munge is not installed or not run as root.
set -euo pipefail
action=$1 dir=$2
here=$(cd "$(dirname "$0")" && pwd)

stop() {
  for name in slurmd slurmctld munge/munged; do
    [ -f "$dir/$name.pid" ] || continue
    pid=$(cat "$dir/$name.pid")
    kill "$pid" 2>/dev/null || true
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$pid" 2>/dev/null || true
    rm -f "$dir/$name.pid"
  done
}

if [ "$action" = stop ]; then stop; exit 0; fi
[ "$action" = start ] || { echo "usage: $0 start|stop DIR" >&2; exit 2; }
for program in munged mungekey slurmctld slurmd sbatch; do
  command -v "$program" >/dev/null || { echo "skip: $program is not installed (scripts/setup.sh installs slurm-wlm and munge)"; exit 77; }
done
[ "$(id -u)" -eq 0 ] || { echo "skip: the local Slurm cluster needs root"; exit 77; }

# Random ports, so that a second cluster or a leftover one (or a system Slurm) does not clash;
# below the kernel's range of ephemeral ports (ip_local_port_range, 32768-60999 by default), where
# any outgoing connection (sshfs's, Slurm's own) may hold the port the daemon wants to bind; and
# not one that a socket holds now (/proc/net/tcp and tcp6 list them in hex).
port() {
  local low=32768 candidate
  read -r low _ < /proc/sys/net/ipv4/ip_local_port_range 2>/dev/null || true
  while :; do
    candidate=$(shuf -i 20000-$((low - 1)) -n 1)
    awk -v p="$(printf '%04X' "$candidate")" 'FNR > 1 { split($2, a, ":"); if (a[2] == p) found = 1 }
        END { exit !found }' /proc/net/tcp /proc/net/tcp6 2>/dev/null || break
  done
  echo "$candidate"
}
host=$(hostname -s)
mkdir -p "$dir/munge" "$dir/state" "$dir/spool"
chmod 755 "$dir"
chown munge:munge "$dir/munge"
chmod 711 "$dir/munge"
sed -e "s|@HOST@|$host|g" -e "s|@DIR@|$dir|g" -e "s|@USER@|$(id -un)|g" \
    -e "s|@CTLD_PORT@|$(port)|g" -e "s|@SLURMD_PORT@|$(port)|g" "$here/slurm.conf.in" > "$dir/slurm.conf"
export SLURM_CONF=$dir/slurm.conf

runuser -u munge -- mungekey --create --keyfile "$dir/munge/munge.key"
runuser -u munge -- munged --key-file "$dir/munge/munge.key" --socket "$dir/munge/munge.socket" \
  --pid-file "$dir/munge/munged.pid" --log-file "$dir/munge/munged.log" --seed-file "$dir/munge/munged.seed"
slurmctld -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF"

for _ in $(seq 120); do
  state=$(sinfo -h -N -o %t 2>/dev/null || true)
  if [ "$state" = idle ]; then echo "export SLURM_CONF=$SLURM_CONF"; exit 0; fi
  sleep 0.5
done
echo "local Slurm: the node is not idle after 60 s (sinfo: ${state:-no answer}); logs in $dir" >&2
tail -n 20 "$dir/slurmctld.log" "$dir/slurmd.log" >&2 || true
stop
exit 1
