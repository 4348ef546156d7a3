#!/usr/bin/env python3
"""Sends the packets of a stream file (spec 10) as UDP datagrams, one packet each, in file order.

    send_datagrams.py FILE.ellc HOST:PORT [MB_PER_SECOND]

Paced (default about 19 MB/s) so that a receiver on the same machine keeps up with the loopback
buffer. Used by bench/run.sh amplification to put hostile recordings through `ellicast receive`.
"""
import socket
import struct
import sys
import time


def packets(data):
    if data[:8] != b"\x89ELC\r\n\x1a\n" or len(data) < 12:
        raise SystemExit(f"send_datagrams: {sys.argv[1]} is not a stream file")
    at = 12
    while at + 24 <= len(data):
        (length,) = struct.unpack_from("<H", data, at + 18)
        yield data[at:at + 24 + length]
        at += 24 + length


def main():
    if len(sys.argv) not in (3, 4):
        raise SystemExit(__doc__)
    host, port = sys.argv[2].rsplit(":", 1)
    rate = float(sys.argv[3]) * 1e6 if len(sys.argv) == 4 else 19e6
    data = open(sys.argv[1], "rb").read()
    s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    start, sent, count = time.monotonic(), 0, 0
    for p in packets(data):
        s.sendto(p, (host, int(port)))
        sent += len(p)
        count += 1
        ahead = sent / rate - (time.monotonic() - start)
        if ahead > 0.001:
            time.sleep(ahead)
    print(f"sent {count} datagrams, {sent} bytes in {time.monotonic() - start:.2f} s", file=sys.stderr)


if __name__ == "__main__":
    main()
