"""``goalagent run --inspect`` end to end in Debian's headless Chromium (driven through
chromedriver by Selenium): the page loads paused, steps a cycle, takes a breakpoint on a
rule and stops there, answers a query, scrolls back through the history, and stays up
after the agents end until Ctrl-C. A page of another origin cannot open its socket, nor
can a page reached through a foreign host name (DNS rebinding). Also: the robot's panels
through the extension seam."""

from __future__ import annotations

import contextlib
import os
import re
import signal
import subprocess
import sys
import threading
from collections.abc import Iterator
from functools import partial
from http.server import SimpleHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from urllib.parse import urlsplit

import pytest
from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.by import By
from selenium.webdriver.support import expected_conditions as when
from selenium.webdriver.support.ui import WebDriverWait

pytestmark = pytest.mark.heavy  # run first (tests/conftest.py)

ROOT = Path(__file__).resolve().parents[3]
CHROMIUM, CHROMEDRIVER = "/usr/bin/chromium", "/usr/bin/chromedriver"
FLAGS = ("--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
         "--disable-component-update", "--no-first-run", "--window-size=1400,1100")
# A list, a quoted atom with brackets and a tag: the page must show them as written.
AGENT = """
init module {
    beliefs { count(0). label('<b>x</b> [c]'). }
    goals { count(3). }
}
main module [exit=nogoals] { program {
    if bel(count(N), N < 3, M is N + 1) then delete(count(N)) + insert(count(M)).
} }
"""


@contextlib.contextmanager
def _inspected_run(folder: Path) -> Iterator[tuple[subprocess.Popen, str]]:
    """``goalagent run counter.goal --inspect --port 0`` in ``folder`` and the page's
    address; killed at the end if still running."""
    program = folder / "counter.goal"
    program.write_text(AGENT)
    process = subprocess.Popen(
        [sys.executable, "-m", "goalagent", "run", str(program), "--inspect", "--port", "0"],
        cwd=folder, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        line = process.stderr.readline()
        match = re.search(r"http://127\.0\.0\.1:(\d+)/\?token=[\w-]+", line)
        assert match, line + process.stderr.read()
        yield process, match.group(0)
    finally:
        if process.poll() is None:
            process.kill()
        process.communicate(timeout=30)


@pytest.fixture
def inspected(tmp_path: Path) -> Iterator[tuple[subprocess.Popen, str]]:
    """A run of its own, for a test that steps and ends it."""
    with _inspected_run(tmp_path) as run:
        yield run


@pytest.fixture(scope="module")
def paused(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[subprocess.Popen, str]]:
    """A run shared by the tests that only look at it or attack it: each leaves it paused
    before its first cycle (what they check)."""
    with _inspected_run(tmp_path_factory.mktemp("paused")) as run:
        yield run


@pytest.fixture(scope="module")
def browser(tmp_path_factory: pytest.TempPathFactory) -> Iterator[webdriver.Chrome]:
    """One Chromium for the module's tests (each opens the pages it needs)."""
    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for flag in FLAGS:
        options.add_argument(flag)
    # a name of another site that resolves to this machine, as after a DNS rebinding
    options.add_argument("--host-resolver-rules=MAP rebound.test 127.0.0.1")
    options.add_argument(f"--user-data-dir={tmp_path_factory.mktemp('chromium-profile')}")
    driver = webdriver.Chrome(service=Service(CHROMEDRIVER), options=options)
    try:
        yield driver
    finally:
        driver.quit()


def _text(driver: webdriver.Chrome, css: str) -> str:
    """The element's text as the page holds it (not as styled, e.g. upper-cased)."""
    return driver.find_element(By.CSS_SELECTOR, css).get_attribute("textContent")


def test_page_steps_breaks_queries_and_scrolls_back(inspected, browser, tmp_path: Path):
    process, url = inspected
    wait = WebDriverWait(browser, 60)
    browser.get(url)
    wait.until(when.text_to_be_present_in_element((By.ID, "status"), "before the first cycle"))
    assert "count(0)" in _text(browser, ".agent .beliefs")
    assert "'<b>x</b> [c]'" in _text(browser, ".agent .beliefs")  # shown as written

    browser.find_element(By.ID, "step").click()
    wait.until(when.text_to_be_present_in_element((By.ID, "status"), "after cycle 1"))
    assert "count(1)" in _text(browser, ".agent .beliefs")
    assert "fired main" in _text(browser, ".agent .events")
    assert "N=0, M=1" in _text(browser, ".agent .events")
    assert _text(browser, ".agent h2") == "counter — cycle 1"  # not "running" while paused

    field = browser.find_element(By.ID, "break-input")
    field.send_keys("counter.goal:7")
    browser.find_element(By.ID, "break-add").click()
    wait.until(when.text_to_be_present_in_element((By.ID, "breakpoints"), "counter.goal:7"))
    browser.find_element(By.ID, "run").click()
    wait.until(when.text_to_be_present_in_element((By.ID, "status"),
                                                  "breakpoint counter.goal:7"))
    assert "counter #2" in _text(browser, "#status") or "cycle 2" in _text(browser, ".agent h2")
    assert "this cycle so far" in _text(browser, ".agent .events")

    query = browser.find_element(By.ID, "query-input")
    query.send_keys("bel(count(X))")
    browser.find_element(By.ID, "query-send").click()
    wait.until(when.text_to_be_present_in_element((By.ID, "query-result"), "X=1"))
    query.clear()
    query.send_keys("bel(count(X)")
    browser.find_element(By.ID, "query-send").click()
    wait.until(lambda driver: "error" in driver.find_element(By.ID, "query-result")
               .get_attribute("class"))

    browser.find_element(By.CSS_SELECTOR, "#breakpoints button").click()  # remove it
    wait.until(lambda driver: not driver.find_elements(By.CSS_SELECTOR, "#breakpoints li"))
    browser.find_element(By.ID, "run").click()
    wait.until(when.text_to_be_present_in_element((By.ID, "status"), "ended"))
    assert "count(3)" in _text(browser, ".agent .beliefs")
    assert "goals (0)" in _text(browser, ".agent .goals")
    assert _text(browser, ".agent h2") == "counter — cycle 3 — terminated"

    browser.execute_script(  # scroll the history back to the first cycle
        "const h = document.getElementById('history'); h.value = h.min;"
        "h.dispatchEvent(new Event('input'));")
    wait.until(when.text_to_be_present_in_element((By.ID, "history-label"), "cycle 1"))
    assert "count(1)" in _text(browser, ".agent .beliefs")
    assert "count(3)" not in _text(browser, ".agent .beliefs")
    browser.find_element(By.ID, "live").click()
    browser.save_screenshot(str(tmp_path / "inspector.png"))
    assert (tmp_path / "inspector.png").stat().st_size > 10_000

    assert process.poll() is None  # the page stays up after the agents end
    process.send_signal(signal.SIGINT)
    out, err = process.communicate(timeout=30)
    assert process.returncode == 0, err
    assert "the page stays up" in err and "inspector: stopped" in err
    assert "counter: terminated after 3 cycles" in err


def test_the_inspector_listens_on_this_machine_only_by_default(paused) -> None:
    _, url = paused
    assert url.startswith("http://127.0.0.1:")


def test_a_taken_port_is_a_clear_error(tmp_path: Path) -> None:
    import socket

    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        port = taken.getsockname()[1]
        program = tmp_path / "a.goal"
        program.write_text("main module { program { if true then print(x). } }\n")
        result = subprocess.run([sys.executable, "-m", "goalagent", "run", str(program),
                                 "--inspect", "--port", str(port)], capture_output=True,
                                text=True, timeout=120, env={**os.environ})
    assert result.returncode == 2, result.stderr
    assert "error: --inspect" in result.stderr and "Traceback" not in result.stderr


# Served from another origin (another port of 127.0.0.1): it knows the inspector's address
# and even its token, opens its socket and tries to run the agents and a query; the title
# says what happened.
FOREIGN_PAGE = """<!doctype html><title>waiting</title><script>
const socket = new WebSocket("ws://127.0.0.1:PORT/ws?token=TOKEN");
socket.onopen = () => { document.title = "opened";
  socket.send(JSON.stringify({op: "run"}));
  socket.send(JSON.stringify({op: "query", agent: "counter", text: "bel(count(X))"})); };
socket.onmessage = (m) => { document.title = "answered " + m.data.slice(0, 40); };
socket.onerror = () => { if (document.title === "waiting") document.title = "refused"; };
</script>"""


@pytest.fixture
def foreign_site(tmp_path: Path) -> Iterator[tuple[Path, str]]:
    """A local web server on another port: its folder and its address."""
    folder = tmp_path / "site"
    folder.mkdir()
    handler = partial(SimpleHTTPRequestHandler, directory=str(folder))
    handler.log_message = lambda *args: None  # type: ignore[attr-defined]
    server = ThreadingHTTPServer(("127.0.0.1", 0), handler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield folder, f"http://127.0.0.1:{server.server_address[1]}"
    finally:
        server.shutdown()
        thread.join(timeout=10)


def test_a_page_of_another_origin_cannot_open_the_socket(paused, browser, foreign_site):
    process, url = paused
    parts = urlsplit(url)
    folder, site = foreign_site
    (folder / "attack.html").write_text(FOREIGN_PAGE.replace("PORT", str(parts.port))
                                        .replace("TOKEN", parts.query.split("=", 1)[1]))
    browser.get(f"{site}/attack.html")
    WebDriverWait(browser, 30).until(lambda driver: driver.title != "waiting")
    assert browser.title == "refused"
    # the run is where it was: paused before the first cycle
    browser.get(url)
    WebDriverWait(browser, 60).until(when.text_to_be_present_in_element(
        (By.ID, "status"), "before the first cycle"))
    assert "count(0)" in _text(browser, ".agent .beliefs")
    assert process.poll() is None


def test_a_page_reached_through_another_host_name_is_refused(paused, browser):
    # DNS rebinding: a page of rebound.test whose name now resolves to 127.0.0.1
    _, url = paused
    parts = urlsplit(url)
    browser.get(f"http://rebound.test:{parts.port}/?{parts.query}")
    assert "forbidden" in browser.find_element(By.TAG_NAME, "body").text
    assert "Host" in browser.find_element(By.TAG_NAME, "body").text
    browser.get(url)  # the right address with the right token is served
    WebDriverWait(browser, 60).until(when.text_to_be_present_in_element(
        (By.ID, "status"), "before the first cycle"))
    browser.get(f"http://127.0.0.1:{parts.port}/")  # without the token: refused
    assert "token" in browser.find_element(By.TAG_NAME, "body").text
