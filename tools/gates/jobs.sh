# tools/gates/jobs.sh -- sourced by the proof scripts: at most $JOBS background jobs.
#
# Usage:  pids=""; for x in ...; do work "$x" & pids="$pids $!"; throttle; done; wait
# throttle returns once fewer than $JOBS of the processes in $pids are alive, and
# drops the finished ones from $pids.  (A plain 'jobs -p' cannot be used: in
# dash it runs in a subshell that sees no jobs, so it never limits anything.)
throttle() {
    while :; do
        n=0
        live=""
        for p in $pids; do
            if kill -0 "$p" 2>/dev/null; then
                n=$((n + 1))
                live="$live $p"
            fi
        done
        pids=$live
        [ "$n" -lt "$JOBS" ] && break
        sleep 0.5
    done
}
