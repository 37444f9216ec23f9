#!/usr/bin/env python3
"""A headless screenshot of `lagrange view`'s page, taken once the page says
it is drawn: it waits for <body data-ready="true"> (viewer.js sets it an
animation frame after the first frame of the arm and its plots is drawn;
"error" when the run cannot be loaded). Without waiting, a screenshot taken
at the page's load is blank: the log is still on its way.

    lagrange view runs/flex &
    python3 tools/view/screenshot.py http://127.0.0.1:8642/ view.png --at 0.15

Headless chromium driven over WebDriver by chromedriver (Debian's chromium
and chromium-driver); standard library only. Exit 0 with the file written,
1 when the page is not ready in time or reports an error, 2 on bad arguments.
See docs/viewer.md.
"""

import argparse
import base64
import json
import os
import shutil
import socket
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request

CHROMIUM_ARGS = [
    "--headless", "--no-sandbox", "--disable-gpu", "--enable-unsafe-swiftshader",  # WebGL in software
    "--no-first-run", "--disable-background-networking", "--disable-component-update", "--disable-sync",
    "--force-device-scale-factor=1",
]


class Failed(Exception):
    """What went wrong, said as the message the program ends with."""


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


# Never through a proxy from the environment: the page and chromedriver are on loopback.
OPENER = urllib.request.build_opener(urllib.request.ProxyHandler({}))


def call(base, method, path, body=None, timeout=60):
    data = None if body is None else json.dumps(body).encode()
    request = urllib.request.Request(base + path, data=data, method=method,
                                     headers={"Content-Type": "application/json"})
    try:
        with OPENER.open(request, timeout=timeout) as response:
            return json.loads(response.read() or b"{}").get("value")
    except urllib.error.HTTPError as e:
        value = json.loads(e.read() or b"{}").get("value", {})
        raise Failed("chromedriver refused %s %s: %s" % (method, path, value.get("message", e))) from None


def wait_for(what, seconds, probe):
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        value = probe()
        if value:
            return value
        time.sleep(0.05)
    raise Failed("%s within %g s" % (what, seconds))


def parse_size(text):
    try:
        width, height = (int(v) for v in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError("%r is not WIDTHxHEIGHT in pixels, e.g. 1280x720" % text) from None
    if not (100 <= width <= 8000 and 100 <= height <= 8000):
        raise argparse.ArgumentTypeError("%r: expected each side 100 to 8000 pixels" % text)
    return width, height


def check_served(url):
    """The page's server answers, asked before chromedriver starts: a URL
    nothing serves is named at once -- and never served by chromedriver
    itself, whose free port may be the one a stopped viewer had."""
    try:
        with OPENER.open(url, timeout=5) as response:
            response.read(1)
    except urllib.error.HTTPError:
        return  # it answers (with an error page the browser will show)
    except (urllib.error.URLError, OSError) as e:
        reason = getattr(e, "reason", e)
        raise Failed("cannot open %s (%s); expected the URL lagrange view printed, while it serves" % (
            url, reason)) from None


def screenshot(args, work):
    driver = shutil.which("chromedriver")
    if driver is None:
        raise Failed("chromedriver is not installed; on Debian 12: sudo apt-get install chromium chromium-driver")
    check_served(args.url)
    port = free_port()
    env = dict(os.environ)
    env.pop("DISPLAY", None)  # headless chromium given a display it cannot reach makes no WebGL context
    with open(os.path.join(work, "chromedriver.log"), "wb") as log:
        process = subprocess.Popen([driver, "--port=%d" % port], stdout=log, stderr=log, env=env)
    base = "http://127.0.0.1:%d" % port
    session = None
    try:
        def driver_ready():
            try:
                return call(base, "GET", "/status", timeout=2).get("ready")
            except (OSError, Failed):
                return None
        wait_for("chromedriver did not start", 20, driver_ready)
        options = {"binary": args.chromium, "args": CHROMIUM_ARGS + [
            "--window-size=%d,%d" % args.size, "--user-data-dir=" + os.path.join(work, "profile")]}
        session = call(base, "POST", "/session", {"capabilities": {"alwaysMatch": {
            "browserName": "chrome", "goog:chromeOptions": options}}})["sessionId"]
        page = "/session/" + session

        def run(script, *arguments):
            return call(base, "POST", page + "/execute/sync", {"script": script, "args": list(arguments)})

        try:
            call(base, "POST", page + "/url", {"url": args.url})
        except Failed as e:
            raise Failed("cannot open %s (%s); expected the URL lagrange view printed, while it serves" % (
                args.url, str(e).split(": ", 1)[-1].splitlines()[0])) from None
        ready = wait_for("the page at %s did not set data-ready" % args.url, args.timeout,
                         lambda: run("return document.body.dataset.ready || null;"))
        if ready != "true":
            raise Failed("the page at %s says data-ready=%s: %s" % (
                args.url, ready, run("return document.getElementById('status').textContent;")))
        if args.at is not None:  # seek as the slider does, then wait for that frame on the screen
            run("const s = document.getElementById('seek'); s.value = arguments[0];"
                "s.dispatchEvent(new Event('input'));", args.at)
            wait_for("the frame at t = %g s was not drawn" % args.at, args.timeout, lambda: run(
                "const s = window.lagrangeViewer.state(); return s.presentedT === s.t;"))
        png = base64.b64decode(call(base, "GET", page + "/screenshot"))
        with open(args.out, "wb") as f:
            f.write(png)
    finally:
        if session is not None:
            try:
                call(base, "DELETE", "/session/" + session, timeout=10)
            except (OSError, Failed):
                pass
        process.terminate()
        process.wait(10)


def main():
    parser = argparse.ArgumentParser(description="Screenshot lagrange view's page headless, once it is drawn.")
    parser.add_argument("url", help="the URL lagrange view printed, e.g. http://127.0.0.1:8642/")
    parser.add_argument("out", help="the PNG file to write")
    parser.add_argument("--at", type=float, metavar="SECONDS", help="seek to this time of the log first")
    parser.add_argument("--size", type=parse_size, default=(1280, 720), metavar="WxH",
                        help="the browser window in pixels; the page gets a little less (default 1280x720)")
    parser.add_argument("--timeout", type=float, default=60.0, metavar="SECONDS",
                        help="how long to wait for the page (default 60)")
    parser.add_argument("--chromium", default="/usr/bin/chromium", help="the browser (default /usr/bin/chromium)")
    args = parser.parse_args()
    try:
        with tempfile.TemporaryDirectory(prefix="lagrange-screenshot-") as work:
            screenshot(args, work)
    except Failed as e:
        sys.exit("screenshot.py: %s" % e)
    print("screenshot.py: wrote %s" % args.out)


if __name__ == "__main__":
    main()
