#!/usr/bin/env python3
"""Load test of `bzspline serve` from a second process on loopback.

Starts the server (port 0, --quiet), then, bounded in count and time:

1. concurrent fits: WORKERS threads, each sending REQUESTS POST /api/fit on
   one keep-alive connection; counts statuses and latencies; samples the
   server's resident memory (VmRSS from /proc) before, after a first round
   and after a second identical round (memory must not keep growing);
2. slow clients: SLOW connections that send a fit request's body one byte per
   second (slowloris), while one ordinary client keeps fitting and measures
   its latency and errors;
3. oversized bodies: a declared Content-Length above --max-body, and a
   chunked body that grows past it; both must be refused with 413 quickly
   while the ordinary client keeps working.

Every phase has a deadline; the server is stopped at the end. Prints a
summary and exits non-zero when an ordinary request failed with something
other than the documented refusals.

Usage: python3 bench/serve_load.py [--bin target/release/bzspline]
       [--workers 4] [--requests 500] [--points 200] [--slow 8]
"""

import argparse
import http.client
import json
import math
import os
import random
import socket
import statistics
import subprocess
import sys
import threading
import time


def rss_kb(pid):
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    return -1


def body(points, rng):
    xs = sorted(rng.sample(range(points * 10), points))
    pts = [[x / 10.0, math.sin(x / 37.0) + rng.uniform(-0.1, 0.1)] for x in xs]
    return json.dumps({"points": pts, "alpha": 0.5, "samples": 4}).encode()


def percentile(values, p):
    if not values:
        return float("nan")
    values = sorted(values)
    return values[min(len(values) - 1, int(p / 100.0 * len(values)))]


class Client:
    """One keep-alive connection; reconnects after an error."""

    def __init__(self, port):
        self.port = port
        self.conn = None

    def post(self, payload, timeout=10.0):
        if self.conn is None:
            self.conn = http.client.HTTPConnection("127.0.0.1", self.port, timeout=timeout)
        t = time.perf_counter()
        try:
            self.conn.request(
                "POST", "/api/fit", body=payload,
                headers={"Content-Type": "application/json", "Host": f"127.0.0.1:{self.port}"},
            )
            r = self.conn.getresponse()
            data = r.read()
            status = r.status
            if status == 200:
                out = json.loads(data)
                assert "segments" in out or "svg_path" in out, list(out)[:5]
        except Exception as e:  # noqa: BLE001 - any failure is counted
            self.conn.close()
            self.conn = None
            status = f"exception {type(e).__name__}"
        return status, time.perf_counter() - t


def fit_round(port, workers, requests, points, deadline):
    statuses = {}
    latencies = []
    lock = threading.Lock()

    def work(seed):
        rng = random.Random(seed)
        c = Client(port)
        payloads = [body(points, rng) for _ in range(8)]
        for i in range(requests):
            if time.monotonic() > deadline:
                break
            s, dt = c.post(payloads[i % len(payloads)])
            with lock:
                statuses[s] = statuses.get(s, 0) + 1
                latencies.append(dt)

    threads = [threading.Thread(target=work, args=(k,)) for k in range(workers)]
    t = time.perf_counter()
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    return statuses, latencies, time.perf_counter() - t


def slow_client(port, payload, stop, results):
    """Sends the headers at once, then the body one byte per second."""
    try:
        s = socket.create_connection(("127.0.0.1", port), timeout=30)
        head = (
            f"POST /api/fit HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n"
            f"Content-Type: application/json\r\nContent-Length: {len(payload)}\r\n\r\n"
        ).encode()
        s.sendall(head)
        s.settimeout(0.01)
        for b in payload:
            if stop.is_set():
                break
            try:
                s.sendall(bytes([b]))
            except OSError:
                break
            try:
                reply = s.recv(200)
                if reply:
                    results.append(reply.split(b"\r\n", 1)[0].decode(errors="replace"))
                    break
            except (socket.timeout, BlockingIOError):
                pass
            except OSError:
                break
            stop.wait(1.0)
        s.close()
    except OSError as e:
        results.append(f"exception {e}")


def ordinary_client(port, payload, stop, seconds):
    c = Client(port)
    statuses, latencies = {}, []
    end = time.monotonic() + seconds
    while time.monotonic() < end and not stop.is_set():
        s, dt = c.post(payload)
        statuses[s] = statuses.get(s, 0) + 1
        latencies.append(dt)
        time.sleep(0.02)
    return statuses, latencies


def summary(name, statuses, latencies):
    ms = [x * 1e3 for x in latencies]
    print(
        f"  {name}: {sum(statuses.values())} requests, statuses {statuses}, "
        f"latency ms p50 {percentile(ms, 50):.2f} p99 {percentile(ms, 99):.2f} "
        f"max {max(ms) if ms else float('nan'):.2f}"
    )


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", default="target/release/bzspline")
    ap.add_argument("--workers", type=int, default=4)
    ap.add_argument("--requests", type=int, default=500)
    ap.add_argument("--points", type=int, default=200)
    ap.add_argument("--slow", type=int, default=8)
    ap.add_argument("--slow-seconds", type=float, default=12.0)
    ap.add_argument("--max-body", type=int, default=1 << 20)
    ap.add_argument("--time-limit", type=float, default=120.0)
    args = ap.parse_args()

    server = subprocess.Popen(
        [args.bin, "serve", "--port", "0", "--quiet", "--max-body", str(args.max_body)],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
    )
    failed = False
    try:
        line = server.stdout.readline()
        port = int(line.strip().rstrip("/").rsplit(":", 1)[1])
        print(f"server pid {server.pid} on port {port}: {line.strip()}")
        start = time.monotonic()
        deadline = start + args.time_limit
        rss0 = rss_kb(server.pid)

        print(f"1. concurrent fits: {args.workers} workers x {args.requests} requests, "
              f"{args.points} points each")
        rounds = []
        for r in range(2):
            st, lat, wall = fit_round(port, args.workers, args.requests, args.points, deadline)
            rounds.append(rss_kb(server.pid))
            summary(f"round {r + 1} ({wall:.1f} s, {sum(st.values()) / wall:.0f} fits/s)", st, lat)
            bad = {k: v for k, v in st.items() if k != 200}
            if bad:
                failed = True
        print(f"  server VmRSS kB: start {rss0}, after round 1 {rounds[0]}, after round 2 {rounds[1]}")

        payload = body(args.points, random.Random(7))
        stop = threading.Event()
        base_st, base_lat = ordinary_client(port, payload, stop, 3.0)
        print("2. slow clients")
        summary("ordinary client alone", base_st, base_lat)
        results = []
        slow = [threading.Thread(target=slow_client, args=(port, payload, stop, results))
                for _ in range(args.slow)]
        for th in slow:
            th.start()
        time.sleep(1.0)
        st, lat = ordinary_client(port, payload, stop, min(args.slow_seconds, deadline - time.monotonic()))
        summary(f"ordinary client beside {args.slow} slow clients", st, lat)
        if any(k != 200 for k in st):
            failed = True
        stop.set()
        for th in slow:
            th.join(timeout=5)
        print(f"  slow clients' answers: {sorted(set(results)) or 'none (cut off by the client)'}")

        print("3. oversized bodies")
        out = {}

        def background():
            out["r"] = ordinary_client(port, payload, threading.Event(), 4.0)

        bg = threading.Thread(target=background)
        bg.start()
        time.sleep(1.0)
        t = time.perf_counter()
        s = socket.create_connection(("127.0.0.1", port), timeout=10)
        s.sendall((f"POST /api/fit HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n"
                   f"Content-Type: application/json\r\nContent-Length: {100 << 20}\r\n\r\n").encode())
        reply = s.recv(200).split(b"\r\n", 1)[0].decode(errors="replace")
        s.close()
        print(f"  declared 100 MiB: {reply!r} in {(time.perf_counter() - t) * 1e3:.1f} ms")
        if " 413 " not in reply:
            failed = True
        t = time.perf_counter()
        s = socket.create_connection(("127.0.0.1", port), timeout=10)
        s.sendall((f"POST /api/fit HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n"
                   "Content-Type: application/json\r\nTransfer-Encoding: chunked\r\n\r\n").encode())
        chunk = b"[" + b"0," * 32767
        sent = 0
        reply = ""
        try:
            while sent < 8 * args.max_body:
                s.sendall(f"{len(chunk):x}\r\n".encode() + chunk + b"\r\n")
                sent += len(chunk)
                s.settimeout(0.001)
                try:
                    got = s.recv(200)
                    if got:
                        reply = got.split(b"\r\n", 1)[0].decode(errors="replace")
                        break
                except (socket.timeout, BlockingIOError):
                    pass
                s.settimeout(10)
        except OSError as e:
            reply = reply or f"connection closed ({e.__class__.__name__})"
        if not reply:
            s.settimeout(10)
            try:
                reply = s.recv(200).split(b"\r\n", 1)[0].decode(errors="replace")
            except OSError as e:
                reply = f"connection closed ({e.__class__.__name__})"
        s.close()
        print(f"  chunked body, {sent} bytes sent: {reply!r} in {(time.perf_counter() - t) * 1e3:.1f} ms")
        if "413" not in reply:
            failed = True
        bg.join()
        summary("ordinary client meanwhile (4 s)", *out["r"])
        if any(k != 200 for k in out["r"][0]):
            failed = True
        print(f"  server VmRSS kB at the end: {rss_kb(server.pid)}; "
              f"total {time.monotonic() - start:.1f} s")
    finally:
        server.terminate()
        try:
            server.wait(timeout=5)
        except subprocess.TimeoutExpired:
            server.kill()
    print("FAILED" if failed else "OK")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
