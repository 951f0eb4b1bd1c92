"""Takes docs/inspector.png: the mind inspector on the garbage robot (MuJoCo, camera
perception) after 8 steps, with a condition breakpoint and a query answered.

Run from the repository root: ``MUJOCO_GL=egl .venv/bin/python scripts/inspector_screenshot.py``.
Drives Debian's headless Chromium through chromedriver (both installed by scripts/setup.sh),
as tests/goalagent/inspector/test_inspector.py does; the screenshot is put in place atomically.
"""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import tempfile
from pathlib import Path

from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.by import By
from selenium.webdriver.support import expected_conditions as when
from selenium.webdriver.support.ui import WebDriverWait

from ondisk import write_atomically

ROOT = Path(__file__).resolve().parents[1]
TARGET = ROOT / "docs" / "inspector.png"
STEPS = 8
BREAKPOINT = "bel(percept(opened))"
QUERY = "bel(afford(lid, A, opened, T, S, R))"


def _browser(profile: Path) -> webdriver.Chrome:
    options = webdriver.ChromeOptions()
    options.binary_location = "/usr/bin/chromium"
    for flag in ("--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
                 "--disable-background-networking", "--window-size=1300,2100",
                 f"--user-data-dir={profile}"):
        options.add_argument(flag)
    return webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)


def main() -> int:
    with tempfile.TemporaryDirectory(prefix="inspector-shot-") as work:
        process = subprocess.Popen(
            [sys.executable, "-m", "goalagent", "run", "agents/garbage_disposal.mas2g",
             "--inspect", "--port", "0"],
            cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
            env={**os.environ, "MUJOCO_GL": os.environ.get("MUJOCO_GL", "egl")})
        assert process.stderr is not None
        try:
            line = process.stderr.readline()
            match = re.search(r"http://127\.0\.0\.1:\d+/\?token=[\w-]+", line)
            if match is None:
                print(line + process.stderr.read(), file=sys.stderr)
                return 1
            browser = _browser(Path(work) / "profile")
            try:
                wait = WebDriverWait(browser, 300)
                browser.get(match.group(0))
                status = (By.ID, "status")
                wait.until(when.text_to_be_present_in_element(status, "before the first cycle"))
                for cycle in range(1, STEPS + 1):
                    browser.find_element(By.ID, "step").click()
                    wait.until(when.text_to_be_present_in_element(status, f"after cycle {cycle}"))
                browser.find_element(By.ID, "break-input").send_keys(BREAKPOINT)
                browser.find_element(By.ID, "break-add").click()
                wait.until(when.text_to_be_present_in_element((By.ID, "breakpoints"),
                                                              BREAKPOINT))
                browser.find_element(By.ID, "query-input").send_keys(QUERY)
                browser.find_element(By.ID, "query-send").click()
                wait.until(when.text_to_be_present_in_element((By.ID, "query-result"), "A="))
                write_atomically(TARGET, browser.get_screenshot_as_png())
            finally:
                browser.quit()
        finally:
            process.send_signal(signal.SIGINT)
            try:
                process.communicate(timeout=60)
            except subprocess.TimeoutExpired:
                process.kill()
    print(f"wrote {TARGET}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
