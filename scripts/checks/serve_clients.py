"""phongcl serve against clients that do not play along, on loopback, with real sockets.

1. Hostile requests (the probe's, and more): each gets a 4xx with a JSON error and the server keeps
   answering.
2. Slow clients: idle sockets, connections sending one header line every 2 s, every long poll the
   server allows and one more (503); meanwhile the page and /api/stats are timed.
3. SIGTERM while such clients are connected (and one not reading a large response): time to exit.
4. Memory: repeated 5 MB scene PUTs (60,000 materials, light linking), each shaded; RSS sampled.
5. Kernels: scenes with a new mix of light counts each (one kernel each, more than the program cache
   keeps in memory), each shaded, from an empty disk cache; RSS and the disk cache sampled.

Prints one line of figures per part; exits 1 on the first failure (part 5 prints figures only: the
program cache's eviction is held by ctest's ProgramCache test, with limits small enough to see). Bounded: every client has a
timeout and the whole run takes about a minute.
"""
import argparse
import json
import os
import signal
import socket
import statistics
import subprocess
import sys
import threading
import time

ANSWER_BOUND_S = 1.0  # the page and the API while slow clients are connected
STOP_BOUND_S = 2.0    # SIGTERM to exit, whatever the clients do


def fail(message):
    print(f"55-serve-clients: FAILED: {message}", file=sys.stderr)
    sys.exit(1)


class Serve:
    """`phongcl serve` on an ephemeral port, its output read until it prints its URL."""

    def __init__(self, phongcl, scene, work, env=None):
        self.log_path = os.path.join(work, f"serve-{time.monotonic_ns()}.log")
        self.log = open(self.log_path, "w")
        self.process = subprocess.Popen([phongcl, "serve", "--scene", scene, "--port", "0"],
                                        stdout=self.log, stderr=subprocess.STDOUT, env=env)
        deadline = time.monotonic() + 120
        while time.monotonic() < deadline:
            text = open(self.log_path).read()
            if "url        http://" in text:
                self.port = int(text.split("url        http://127.0.0.1:")[1].split("/")[0])
                return
            if self.process.poll() is not None:
                fail(f"serve exited: {text}")
            time.sleep(0.05)
        fail("serve did not print its URL within 120 s")

    def rss_mb(self):
        with open(f"/proc/{self.process.pid}/status") as status:
            for line in status:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1]) / 1024
        return 0.0

    def stop(self):
        if self.process.poll() is None:
            self.process.kill()
            self.process.wait()
        self.log.close()


def connect(port, timeout=30):
    client = socket.create_connection(("127.0.0.1", port), timeout=timeout)
    client.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
    return client


def read_response(client):
    """One response: (status, headers text, body bytes); status 0 when the server closed first."""
    data = b""
    while b"\r\n\r\n" not in data:
        chunk = client.recv(65536)
        if not chunk:
            return 0, "", data
        data += chunk
    head, body = data.split(b"\r\n\r\n", 1)
    head_text = head.decode("latin-1")
    if head_text.startswith("HTTP/1.1 100"):
        return 100, head_text, body
    length = 0
    for line in head_text.split("\r\n")[1:]:
        name, _, value = line.partition(":")
        if name.lower() == "content-length":
            length = int(value)
    while len(body) < length:
        chunk = client.recv(65536)
        if not chunk:
            break
        body += chunk
    return int(head_text[9:12]), head_text, body


def request(port, raw, timeout=30):
    with connect(port, timeout) as client:
        client.sendall(raw)
        return read_response(client)


def http(method, path, body=b"", content_type="application/json"):
    head = f"{method} {path} HTTP/1.1\r\nHost: 127.0.0.1\r\n"
    if body or method in ("PUT", "POST"):
        head += f"Content-Type: {content_type}\r\nContent-Length: {len(body)}\r\n"
    return head.encode() + b"\r\n" + body


def hostile_requests(port, scene_text):
    deep = b"[" * 50000 + b"]" * 50000
    scene = json.loads(scene_text)
    nan_scene = scene_text.replace("0.6", "NaN", 1).encode()
    cases = [
        (b"GET /%ff HTTP/1.1\r\n\r\n", 404),
        (b"GET /\xff\xfe HTTP/1.1\r\n\r\n", 404),
        (b"GET /api/%c0%af HTTP/1.1\r\n\r\n", 404),
        (b"GET /api/image?%ff=1 HTTP/1.1\r\n\r\n", 400),
        (b"GET /api/image?format=%ff HTTP/1.1\r\n\r\n", 400),
        (b"GET /api/image?exposure=nan HTTP/1.1\r\n\r\n", 400),
        (b"GET /api/image?exposure=1e308 HTTP/1.1\r\n\r\n", 400),
        (b"GET /api/image?width=0 HTTP/1.1\r\n\r\n", 400),
        (b"GET /api/frame?after=-1 HTTP/1.1\r\n\r\n", 400),
        (b"GET /api/frame?timeout_ms=99999999999999999999 HTTP/1.1\r\n\r\n", 400),
        (b"GET /api/pick?x=1e99&y=0 HTTP/1.1\r\n\r\n", 400),
        (b"GET /api/pick?x=1&x=2&y=0 HTTP/1.1\r\n\r\n", 400),
        (b"GET /api/stats?unknown=1 HTTP/1.1\r\n\r\n", 400),
        (http("PUT", "/api/scene", b'{"lights": "\xff"}'), 400),
        (http("PUT", "/api/scene", b"\xc0\xaf"), 400),
        (http("PUT", "/api/scene", deep), 400),
        (http("PUT", "/api/scene", nan_scene), 400),
        (http("PUT", "/api/scene", scene_text.replace("0.6", "1e309", 1).encode()), 400),
        (http("PUT", "/api/scene", json.dumps({**scene, "unknown": 1}).encode()), 400),
        (http("PUT", "/api/scene", scene_text.encode(), "application/x-www-form-urlencoded"), 415),
        (http("PUT", "/api/scene", scene_text.encode(), "multipart/form-data; boundary=x"), 415),
        (http("PUT", "/api/settings", b'{"precision": "\xc3\x28"}'), 400),
        (http("PUT", "/api/settings", b'{"precision": "bogus"}'), 400),
        (b"PUT /api/scene HTTP/1.1\r\nTransfer-Encoding: chunked\r\n\r\n5\r\nhello\r\n0\r\n\r\n", 411),
        (b"PUT /api/scene HTTP/1.1\r\nContent-Length: 99999999999\r\n\r\n", 413),
        (b"PUT /api/scene HTTP/1.1\r\nContent-Length: -1\r\n\r\n", 400),
        (b"GET / HTTP/1.1\r\nX: " + b"a" * 70000 + b"\r\n\r\n", 431),
        (b"GET /" + b"a" * 9000 + b" HTTP/1.1\r\n\r\n", 414),
        (b"BREW / HTTP/1.1\r\n\r\n", 400),
        # Range is not read: an error's JSON body comes whole, not cut to the bytes asked for.
        (b"GET /nowhere HTTP/1.1\r\nRange: bytes=0-3\r\n\r\n", 404),
        (http("POST", "/api/save"), 409),
    ]
    for raw, expected in cases:
        status, head, body = request(port, raw)
        if status != expected:
            fail(f"{raw[:60]!r}: status {status}, expected {expected}: {body[:200]!r}")
        try:
            message = json.loads(body)["error"]
        except (ValueError, KeyError):
            fail(f"{raw[:60]!r}: no JSON error body: {body[:200]!r}")
        if "\n" in message:
            fail(f"{raw[:60]!r}: a multi-line error: {message!r}")
        alive, _, _ = request(port, http("GET", "/api/stats"))
        if alive != 200:
            fail(f"after {raw[:60]!r} the server answers {alive}")
    return len(cases)


class SlowSenders:
    """Connections that send a request's head one header line every `interval` seconds, never ending it."""

    def __init__(self, port, count, interval):
        self.stop = threading.Event()
        self.threads = [threading.Thread(target=self.send, args=(port, interval)) for _ in range(count)]
        for thread in self.threads:
            thread.start()

    def send(self, port, interval):
        with connect(port) as client:
            client.sendall(b"GET /api/stats HTTP/1.1\r\n")
            while not self.stop.wait(interval):
                try:
                    client.sendall(b"X-Slow: 1\r\n")
                except OSError:
                    return

    def end(self):
        self.stop.set()
        for thread in self.threads:
            thread.join()


def slow_clients(port):
    idle = [connect(port) for _ in range(200)]
    senders = SlowSenders(port, 32, 2.0)
    status, head, _ = request(port, http("GET", "/api/image?format=jpeg"), timeout=120)
    version = int(head.split("X-Frame-Version: ")[1].split("\r\n")[0])
    polls = []
    for _ in range(8):
        client = connect(port, timeout=120)
        client.sendall(http("GET", f"/api/frame?timeout_ms=60000&after={version}"))
        polls.append(client)
    time.sleep(0.5)  # the polls reach their workers
    beyond, _, body = request(port, http("GET", f"/api/frame?timeout_ms=60000&after={version}"))
    if beyond != 503:
        fail(f"a long poll beyond the limit got {beyond}: {body[:200]!r}")

    times = []
    for _ in range(20):
        for path in ("/api/stats", "/"):
            start = time.monotonic()
            status, _, _ = request(port, http("GET", path), timeout=10)
            times.append(time.monotonic() - start)
            if status != 200:
                fail(f"{path} answered {status} while slow clients were connected")
        time.sleep(0.1)
    senders.end()
    for client in idle + polls:
        client.close()
    if max(times) > ANSWER_BOUND_S:
        fail(f"answers took up to {max(times) * 1000:.0f} ms (bound {ANSWER_BOUND_S * 1000:.0f} ms)")
    return len(idle), len(senders.threads), len(polls), statistics.median(times), max(times)


def stop_time(serve):
    port = serve.port
    sender = SlowSenders(port, 1, 0.5)
    not_reading = connect(port, timeout=120)
    not_reading.sendall(http("GET", "/api/image?format=exr") * 8)
    poll = connect(port, timeout=120)
    poll.sendall(http("GET", "/api/frame?timeout_ms=60000&after=999999"))
    time.sleep(1.0)
    start = time.monotonic()
    serve.process.send_signal(signal.SIGTERM)
    try:
        code = serve.process.wait(timeout=60)
    except subprocess.TimeoutExpired:
        fail("serve did not exit within 60 s of SIGTERM")
    elapsed = time.monotonic() - start
    sender.end()
    not_reading.close()
    poll.close()
    if code != 0:
        fail(f"serve exited with {code} on SIGTERM")
    if elapsed > STOP_BOUND_S:
        fail(f"SIGTERM took {elapsed:.2f} s to stop the server (bound {STOP_BOUND_S} s)")
    return elapsed


def big_scene(base, materials, lights):
    scene = json.loads(base)
    count = len(scene["materials"])
    scene["materials"] = [{"name": f"m{i}", "ka": [0.1, 0.1, 0.1], "kd": [0.5, 0.4, 0.3], "ks": [0.2, 0.2, 0.2],
                           "shininess": 20 + i % 50} for i in range(materials)]
    scene["lights"] = [{"type": "point", "position": [i % 7 - 3, 4, i % 5 - 2], "color": [0.2, 0.2, 0.2],
                        "materials": list(range(i % count, materials, 97))} for i in range(lights)]
    return json.dumps(scene).encode()


def memory(serve, scene_text, puts):
    port = serve.port
    body = big_scene(scene_text, 60000, 8)
    samples = []
    for i in range(puts):
        status, _, answer = request(port, http("PUT", "/api/scene", body), timeout=120)
        if status != 200:
            fail(f"a 5 MB scene PUT got {status}: {answer[:200]!r}")
        status, _, _ = request(port, http("GET", "/api/image?format=png"), timeout=120)
        if status != 200:
            fail(f"the image after a 5 MB PUT got {status}")
        samples.append(serve.rss_mb())
    warm = samples[min(4, len(samples) - 1)]
    steady = max(samples[len(samples) // 2:])
    if steady > warm * 1.25 + 50:
        fail(f"RSS grew from {warm:.0f} MB (after 5 PUTs) to {steady:.0f} MB (after {puts}): " +
             ", ".join(f"{s:.0f}" for s in samples))
    return len(body) / 1e6, samples[0], warm, steady, max(samples)


def kernel_mixes(serve, scene_text, mixes, cache):
    """RSS after every 8 new light mixes (points 1-8 x directionals 0-4: a kernel each), and the disk cache."""
    scene = json.loads(scene_text)
    samples = []
    for mix in range(mixes):
        points, directionals = 1 + mix % 8, mix // 8
        scene["lights"] = ([{"type": "point", "position": [i % 7 - 3, 4, i % 5 - 2], "color": [0.1, 0.1, 0.1]}
                            for i in range(points)] +
                           [{"type": "directional", "direction": [i % 3 - 1, -1, -0.5], "color": [0.1, 0.1, 0.1]}
                            for i in range(directionals)])
        status, _, answer = request(serve.port, http("PUT", "/api/scene", json.dumps(scene).encode()), timeout=120)
        if status != 200:
            fail(f"a scene of {points} point and {directionals} directional lights got {status}: {answer[:200]!r}")
        status, _, _ = request(serve.port, http("GET", "/api/image?format=png"), timeout=120)
        if status != 200:
            fail(f"the image of light mix {mix + 1} got {status}")
        if (mix + 1) % 8 == 0:
            samples.append(serve.rss_mb())
    files = [os.path.join(cache, name) for name in os.listdir(cache)] if os.path.isdir(cache) else []
    return samples, len(files), sum(os.path.getsize(f) for f in files) / 1e6


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--phongcl", required=True)
    parser.add_argument("--scene", required=True)
    parser.add_argument("--work", required=True)
    parser.add_argument("--puts", type=int, default=30)
    parser.add_argument("--mixes", type=int, default=40)
    args = parser.parse_args()
    scene_text = open(args.scene).read()

    serve = Serve(args.phongcl, args.scene, args.work)
    try:
        tried = hostile_requests(serve.port, scene_text)
        print(f"55-serve-clients: {tried} hostile requests, each a 4xx with a one-line JSON error, "
              f"the server answering after every one")
        idle, senders, polls, median, worst = slow_clients(serve.port)
        print(f"55-serve-clients: with {idle} idle sockets, {senders} connections sending a header line "
              f"every 2 s and {polls} long polls held (one more: 503), the page and /api/stats answered "
              f"40 times in {median * 1000:.1f} ms median, {worst * 1000:.1f} ms worst (bound "
              f"{ANSWER_BOUND_S * 1000:.0f} ms)")
        elapsed = stop_time(serve)
        print(f"55-serve-clients: SIGTERM with a slow sender, a client not reading 8 EXR responses and a "
              f"long poll connected: stopped in {elapsed:.2f} s (bound {STOP_BOUND_S:.0f} s)")
    finally:
        serve.stop()

    serve = Serve(args.phongcl, args.scene, args.work)
    try:
        size, first, warm, steady, peak = memory(serve, scene_text, args.puts)
        print(f"55-serve-clients: {args.puts} PUTs of a {size:.1f} MB scene (60,000 materials, 8 linked "
              f"lights), each shaded: RSS {first:.0f} MB after the first, {warm:.0f} MB after 5, "
              f"{steady:.0f} MB steady (second half), {peak:.0f} MB peak")
    finally:
        serve.stop()

    cache = os.path.join(args.work, "phongcl-cache")
    serve = Serve(args.phongcl, args.scene, args.work, env={**os.environ, "PHONGCL_CACHE_DIR": cache})
    try:
        samples, files, megabytes = kernel_mixes(serve, scene_text, args.mixes, cache)
        print(f"55-serve-clients: {args.mixes} light mixes (a kernel each; 32 kept in memory), each shaded: RSS "
              f"{', '.join(f'{s:.0f}' for s in samples)} MB after every 8; disk cache {files} files, "
              f"{megabytes:.1f} MB")
    finally:
        serve.stop()


if __name__ == "__main__":
    main()
