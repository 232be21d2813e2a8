#!/usr/bin/env bash
# `zenith live` end to end: packet streams recorded from a real FlightGear flight
# (tests/data/live/README.md) are sent again at their recorded timing into `zenith live` on
# loopback, with a few malformed datagrams first; live_check then compares the frames it wrote
# with the packets (positions, attitudes, clock), and SIGINT / SIGTERM must stop it cleanly
# (exit 130 / 143, every frame whole).
# Usage: live_replay_test.sh zenith udp_stream live_check fixture_dir
set -uo pipefail
zenith=$(realpath "$1")
udp_stream=$(realpath "$2")
live_check=$(realpath "$3")
fixtures=$(realpath "$4")
work=$(mktemp -d)
pids=()
trap 'for p in "${pids[@]}"; do kill "$p" 2>/dev/null; done; rm -rf "$work"' EXIT
source "$(dirname "$0")/../sim/check.sh"

# Malformed datagrams, each for one of the warnings (size, version, value).
{
    echo "# malformed FlightGear native datagrams"
    echo "0.000 00000018"                                   # 4 bytes: size
    printf '0.010 00000017%0808d\n' 0                         # version 23, 408 bytes
    printf '0.020 18000000%0808d\n' 0                         # little-endian version 24
} >"$work/bad-native.udprec"
{
    echo "# malformed generic lines"
    printf '0.000 %s\n' "$(printf '2024-06-21T03:30:07,95,-122,3000,280,2,1' | od -An -tx1 | tr -d ' \n')"
    printf '0.010 %s\n' "$(printf 'hello' | od -An -tx1 | tr -d ' \n')"
} >"$work/bad-generic.udprec"

size=64x36
for protocol in fg-native fg-generic; do
    out=$work/$protocol
    "$zenith" live --"$protocol" 0 --out "$out" --every 0.5 --size $size --duration 300 \
        2>"$work/$protocol.log" &
    pids+=($!)
    eval "pid_${protocol//-/_}=$!"
done
# Wait until both listen (the renderer warms up first), then send the streams side by side.
port_of() { sed -n 's/.*listening for .* on udp 127\.0\.0\.1:\([0-9]*\)$/\1/p' "$work/$1.log"; }
for _ in $(seq 1 600); do
    [[ -n $(port_of fg-native) && -n $(port_of fg-generic) ]] && break
    sleep 0.1
done
check "both receivers listen" test -n "$(port_of fg-native)" -a -n "$(port_of fg-generic)"
senders=()
for protocol in fg-native fg-generic; do
    stream=${protocol#fg-}
    (
        "$udp_stream" send "$work/bad-$stream.udprec" 127.0.0.1 "$(port_of $protocol)"
        "$udp_stream" send "$fixtures/fgfs_$stream.udprec" 127.0.0.1 "$(port_of $protocol)"
    ) 2>>"$work/send.log" &
    senders+=($!)
done
wait "${senders[@]}"
sleep 1
kill -INT "$pid_fg_native"
kill -TERM "$pid_fg_generic"
wait "$pid_fg_native"
rc_native=$?
wait "$pid_fg_generic"
rc_generic=$?
pids=()
cat "$work/fg-native.log" "$work/fg-generic.log"
check "SIGINT stops the native receiver with 130" test "$rc_native" -eq 130
check "SIGTERM stops the generic receiver with 143" test "$rc_generic" -eq 143

rc=$rc_native err=$(cat "$work/fg-native.log")
check "native: the three malformed datagrams are counted and named" \
    exited_saying 130 "3 malformed" "size 4 bytes" "version 23 is not supported" \
    "little-endian"
rc=$rc_generic err=$(cat "$work/fg-generic.log")
check "generic: the two malformed lines are counted and named" \
    exited_saying 143 "2 malformed" "latitude = 95 deg" "1 fields"

# Frames against the packets. The streams are ~40 s long: at least 60 frames at 2 a second.
check "native: frames follow the packets" \
    "$live_check" fg-native "$fixtures/fgfs_native.udprec" "$work/fg-native" 60 64 36
check "generic: frames follow the packets" \
    "$live_check" fg-generic "$fixtures/fgfs_generic.udprec" "$work/fg-generic" 60 64 36
check "no partial frame left behind" test -z "$(find "$work" -name '*.partial')"
report
