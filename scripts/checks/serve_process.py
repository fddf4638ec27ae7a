"""`phongcl serve` on a port of its own choosing, for the scripts that drive it over HTTP (the
browser check, bench/serve_frame_rate.py): started with --port 0, its log read until it prints its URL."""
import re
import subprocess
import time


def start_serve(phongcl, arguments, log):
    """(process, url); RuntimeError with the log when the server exits or prints no URL in 120 s."""
    server = subprocess.Popen([phongcl, "serve", "--port", "0", *arguments], stdout=log, stderr=subprocess.STDOUT)
    deadline = time.time() + 120
    while time.time() < deadline:
        text = open(log.name).read()
        match = re.search(r"url\s+(http://\S+)", text)
        if match:
            return server, match.group(1)
        if server.poll() is not None:
            raise RuntimeError(f"phongcl serve exited: {text}")
        time.sleep(0.05)
    server.kill()
    raise RuntimeError("phongcl serve printed no URL")
