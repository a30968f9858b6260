"""Run by test_subscribe.py in a process of its own: subscribes with busdecode.subscribe,
runs a real `decode --lcm udpm://...` publisher, and prints what arrived as JSON.

The process first moves into a network namespace of its own (as root) with multicast on
its loopback, as tests/lcm/lcm_roundtrip_test.cpp does, so the test needs no network and
neither sees nor disturbs other LCM traffic; without that privilege it uses the host's
network on a port of its own.

    lcm_feed.py DECODE CAPTURE CHANNELS PROTO...
"""

import ctypes
import json
import os
import subprocess
import sys
import threading

import busdecode

CLONE_NEWNET = 0x40000000


def private_network():
    libc = ctypes.CDLL(None, use_errno=True)
    if libc.unshare(CLONE_NEWNET) != 0:
        return False
    for cmd in (["ip", "link", "set", "lo", "up", "multicast", "on"],
                ["ip", "route", "add", "224.0.0.0/4", "dev", "lo"]):
        subprocess.run(cmd, check=True)
    return True


def main():
    decode, capture, channels, *protos = sys.argv[1:]
    port = 7667 if private_network() else 7700 + os.getpid() % 200
    url = f"udpm://239.255.76.67:{port}?ttl=0"
    # UDP has no flow control: big socket buffers, a paced publisher, and both
    # subscriptions read while it publishes.
    listen = url + "&recv_buf_size=4194304"
    every = busdecode.subscribe(listen, until_end=True, timeout=20)
    some = busdecode.subscribe(listen, channels=channels, until_end=True, timeout=20)
    got = {}
    reader = threading.Thread(target=lambda: got.update(some=list(some)))
    reader.start()
    args = [decode, capture, "--lcm", url]
    for p in protos:
        args += ["--proto", p]
    env = dict(os.environ, BUSDECODE_LCM_RATE="2000")
    publisher = subprocess.Popen(args, stdout=subprocess.DEVNULL, env=env)
    got["all"] = list(every)
    reader.join()
    if publisher.wait() != 0:
        sys.exit("decode --lcm failed")
    json.dump(got, sys.stdout)

if __name__ == "__main__":
    main()
