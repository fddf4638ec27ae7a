#!/usr/bin/env python3
"""The frames per second `phongcl serve` delivers while a light is dragged, without a browser: one
client moves a light at 60 Hz (PUT /api/scene, as the page's drag does) while another long-polls
/api/frame for the next frame in the page's own query, and counts the frames it receives. The
browser check (scripts/checks/70-browser.sh) measures the same drag through Chromium, whose JPEG
decoding and drawing share the machine's cores with the server; this measures the server alone.

    build/phongcl gbuffer --scene scenes/large/scene.json --out /tmp/large.exr
    /usr/bin/python3 bench/serve_frame_rate.py --gbuffer /tmp/large.exr [--width 1024] \
        [--query view=Filmic -- --ocio blender]

Prints frames received per second, and medians of the wait for each frame and of the server's own
times for it (X-Shade-Ms: the whole shade; X-Kernel-Ms: the kernel's profiling events).
"""
import argparse
import json
import pathlib
import statistics
import sys
import tempfile
import threading
import time
import urllib.request

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "scripts" / "checks"))
from serve_process import start_serve  # noqa: E402  the browser check's own start


def get(url):
    with urllib.request.urlopen(url, timeout=60) as response:
        return response.status, response.read(), response.headers


def drag(url, scene, stop):
    """Light 0 moves a little every 1/60 s, as a pointer drag sends it."""
    while not stop.is_set():
        scene["lights"][0]["position"][0] += 0.01
        request = urllib.request.Request(url + "api/scene", data=json.dumps(scene).encode(), method="PUT",
                                         headers={"Content-Type": "application/json"})
        urllib.request.urlopen(request, timeout=60).read()
        time.sleep(1 / 60)


def measure(url, query, seconds):
    _, _, headers = get(f"{url}api/frame?after=0&{query}")
    after = int(headers["X-Frame-Version"])
    scene = json.loads(get(url + "api/scene")[1])
    stop = threading.Event()
    dragger = threading.Thread(target=drag, args=(url, scene, stop))
    dragger.start()
    waits, shade, kernel, size = [], [], [], 0
    start = time.time()
    try:
        while time.time() - start < seconds:
            asked = time.time()
            status, body, headers = get(f"{url}api/frame?after={after}&timeout_ms=2000&{query}")
            if status == 204:
                continue
            waits.append(1000 * (time.time() - asked))
            after = int(headers["X-Frame-Version"])
            shade.append(float(headers["X-Shade-Ms"]))
            kernel.append(float(headers["X-Kernel-Ms"]))
            size = len(body)
    finally:
        elapsed = time.time() - start
        stop.set()
        dragger.join()
    return {"fps": len(waits) / elapsed, "wait_ms": statistics.median(waits), "shade_ms": statistics.median(shade),
            "kernel_ms": statistics.median(kernel), "bytes": size}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--phongcl", default=str(ROOT / "build/phongcl"))
    parser.add_argument("--scene", default=str(ROOT / "scenes/large/scene.json"))
    parser.add_argument("--gbuffer", required=True)
    parser.add_argument("--format", default="jpeg", choices=["jpeg", "png"])
    parser.add_argument("--width", type=int, help="stream at this width, as the page's 'stream at display size' asks")
    parser.add_argument("--query", default="", help="more of the frame query, e.g. view=Filmic (with -- --ocio blender)")
    parser.add_argument("--seconds", type=float, default=5)
    parser.add_argument("serve_arguments", nargs="*", help="more `phongcl serve` options, after --")
    args = parser.parse_args()
    query = "&".join(part for part in (f"format={args.format}", args.width and f"width={args.width}", args.query) if part)
    with tempfile.NamedTemporaryFile("w", suffix=".log") as log:
        try:
            server, url = start_serve(args.phongcl, ["--scene", args.scene, "--gbuffer", args.gbuffer,
                                                      *args.serve_arguments], log)
        except RuntimeError as error:
            raise SystemExit(f"serve_frame_rate: {error}")
        try:
            load = pathlib.Path("/proc/loadavg").read_text().split()[:3]
            r = measure(url, query, args.seconds)
        finally:
            server.terminate()
            server.wait(timeout=30)
    print(f"serve_frame_rate: {query}: {r['fps']:.1f} frames/s received while dragging; medians: "
          f"wait {r['wait_ms']:.1f} ms, shade {r['shade_ms']:.1f} ms, kernel {r['kernel_ms']:.1f} ms; "
          f"{r['bytes']} bytes a frame; load before {' '.join(load)}")


if __name__ == "__main__":
    main()
