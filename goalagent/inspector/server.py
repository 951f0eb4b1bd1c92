"""The inspector's web side: a Starlette app (the page and one WebSocket per browser) served
by uvicorn in a thread of its own.

The agents run on another thread (Prolog is bound to it): the server never touches an
agent. It keeps the latest state and the history the run thread publishes, pushes each
state to every browser, answers history requests itself, and hands every other command
(step, run, pause, breakpoints, queries) to the run thread through a queue; their replies
come back through :meth:`InspectorServer.reply`. Every request passes ``gate.Gate`` first (the
inspector's own Host and Origin, the run's token); every message is bounded (``gate``).
"""

from __future__ import annotations

import asyncio
import json
import queue
import threading
import time
from collections import deque
from importlib.resources import files
from typing import Any

import uvicorn
from starlette.applications import Starlette
from starlette.responses import HTMLResponse
from starlette.routing import Route, WebSocketRoute
from starlette.websockets import WebSocket, WebSocketDisconnect

from goalagent.inspector.gate import (
    MAX_FRAME,
    MAX_SOCKETS,
    RATE,
    Budget,
    Gate,
    new_token,
    parse_message,
)

HISTORY_LIMIT = 5000  # cycles kept for scrolling back (oldest dropped first)
COMMANDS_WAITING = 200  # commands queued for the run thread at most (beyond: an error)
# What the page is served with: never framed by another page, never cached, no referrer.
_PAGE_HEADERS = {"Content-Security-Policy": "frame-ancestors 'none'",
                 "X-Frame-Options": "DENY", "Cache-Control": "no-store",
                 "Referrer-Policy": "no-referrer", "X-Content-Type-Options": "nosniff"}


class Command:
    """A browser's command for the run thread and the socket its reply goes to."""

    def __init__(self, message: dict[str, Any], socket: WebSocket | None) -> None:
        self.message = message
        self.socket = socket


class InspectorServer:
    """The web server of one run: state, history, sockets, the command queue."""

    def __init__(self, host: str, port: int) -> None:
        self.host = host
        self.token = new_token()
        self.commands: queue.Queue[Command] = queue.Queue(maxsize=COMMANDS_WAITING)
        self._state: dict[str, Any] = {"type": "state", "agents": [], "paused": True}
        self._history: deque[dict[str, Any]] = deque(maxlen=HISTORY_LIMIT)
        self._lock = threading.Lock()
        self._sockets: set[WebSocket] = set()
        # the run's own budget beside each socket's: the run thread answers one command at
        # a time, and 15 pages each sending their burst of queries held it for 35 s
        self._budget = Budget()
        self._loop: asyncio.AbstractEventLoop | None = None
        self._page = files("goalagent.inspector").joinpath("page.html").read_text("utf-8")
        app = Starlette(routes=[Route("/", self._index), WebSocketRoute("/ws", self._socket)])
        self._gate = Gate(app, host, self.token)
        self._server = uvicorn.Server(uvicorn.Config(self._gate, host=host, port=port,
                                                     log_level="warning", lifespan="off",
                                                     ws="websockets-sansio",
                                                     ws_max_size=MAX_FRAME))
        self._thread = threading.Thread(target=self._serve, name="inspector", daemon=True)

    # ------------------------------------------------------------------ life
    def start(self, timeout: float = 30.0) -> int:
        """Serve in the background; returns the port (the one chosen when asked for 0)."""
        self._thread.start()
        deadline = time.monotonic() + timeout
        while not self._server.started:
            if not self._thread.is_alive() or time.monotonic() > deadline:
                raise OSError(f"the inspector could not listen on {self.host}")
            time.sleep(0.02)
        self._gate.port = self._server.servers[0].sockets[0].getsockname()[1]
        return self._gate.port

    def stop(self) -> None:
        self._server.should_exit = True
        self._thread.join(timeout=5)

    def _serve(self) -> None:
        asyncio.run(self._main())

    async def _main(self) -> None:
        self._loop = asyncio.get_running_loop()
        await self._server.serve()

    # ------------------------------------------------------------------ from the run thread
    def publish(self, state: dict[str, Any]) -> None:
        """A new state for every browser."""
        state = {**state, "type": "state", "history": self._history_range()}
        with self._lock:
            self._state = state
        self._send_all(state)

    def record(self, snapshot: dict[str, Any]) -> None:
        """One agent's cycle for the history (numbered in order)."""
        with self._lock:
            index = self._history[-1]["index"] + 1 if self._history else 0
            self._history.append({**snapshot, "index": index})

    def reply(self, command: Command, message: dict[str, Any]) -> None:
        """The run thread's answer to ``command`` (to its browser only)."""
        if command.socket is not None and self._loop is not None:
            asyncio.run_coroutine_threadsafe(self._send(command.socket, message), self._loop)

    # ------------------------------------------------------------------ web
    async def _index(self, request) -> HTMLResponse:
        return HTMLResponse(self._page, headers=_PAGE_HEADERS)

    async def _socket(self, socket: WebSocket) -> None:
        if len(self._sockets) >= MAX_SOCKETS:
            await socket.close(code=1013, reason="too many inspector pages open")
            return
        await socket.accept()
        self._sockets.add(socket)
        with self._lock:
            state = self._state
        await self._send(socket, state)
        budget = Budget()
        try:
            while True:
                frame = await socket.receive()
                if frame["type"] == "websocket.disconnect":
                    break
                if not (budget.take() and self._budget.take()):
                    if budget.warn():
                        await self._send(socket, _error(f"too many messages: at most "
                                                        f"{RATE:g} a second"))
                    continue
                message = parse_message(frame)
                if isinstance(message, str):
                    await self._send(socket, _error(message))
                elif message["op"] == "history":
                    await self._send(socket, self._history_entry(message.get("index")))
                else:
                    try:
                        self.commands.put_nowait(Command(message, socket))
                    except queue.Full:
                        await self._send(socket, _error("the run is busy: too many "
                                                        "commands waiting"))
        except (WebSocketDisconnect, RuntimeError, OSError):
            pass  # the browser went away
        finally:
            self._sockets.discard(socket)

    def _history_range(self) -> list[int]:
        with self._lock:
            if not self._history:
                return []
            return [self._history[0]["index"], self._history[-1]["index"]]

    def _history_entry(self, index: object) -> dict[str, Any]:
        with self._lock:
            if self._history and isinstance(index, int):
                position = index - self._history[0]["index"]
                if 0 <= position < len(self._history):
                    return {"type": "history", "snapshot": self._history[position]}
        return _error(f"no cycle {index} in the history")

    def _send_all(self, message: dict[str, Any]) -> None:
        if self._loop is None:
            return
        for socket in list(self._sockets):
            asyncio.run_coroutine_threadsafe(self._send(socket, message), self._loop)

    @staticmethod
    async def _send(socket: WebSocket, message: dict[str, Any]) -> None:
        try:
            await socket.send_text(json.dumps(message))
        except (RuntimeError, WebSocketDisconnect, OSError):
            pass  # the browser went away


def _error(text: str) -> dict[str, Any]:
    return {"type": "error", "text": text}
