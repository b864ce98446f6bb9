"""How many sessions one served planner keeps, and which one makes room for a new one.

Each session holds a planner instance with its costmap, plan and inputs. A peer that configures
under ever new session ids would grow the worker without end: a hostile one did (a mutated
configure is a new session more often than not), and so would a Nav2 that crashes and starts
again, never sending its cleanup. So a served planner keeps at most MAX_SESSIONS. At the limit,
a new session takes the place of the one called least recently, if no call came for it for
IDLE_S: a stale session's plugin is gone, and a live one whose session ended gets
SessionUnknown on its next call and configures again by itself. When every session was called
within IDLE_S, the new one is refused: the robots being served keep their sessions.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Protocol, TypeVar

#: far above the robots one 2-core host serves (the batched fleet's target is 35)
MAX_SESSIONS = 256
IDLE_S = 60.0


class _Session(Protocol):
    sid: str
    last_call: float


S = TypeVar("S", bound=_Session)


class SessionLimitReached(Exception):
    """A new session was refused: the planner serves its limit, every one of them in use."""


def session_to_end(
    sessions: Mapping[str, S], sid: str, now: float, limit: int = MAX_SESSIONS
) -> S | None:
    """The session to end before ``sid`` is configured (None: there is room, or ``sid`` is
    already one of them). Raises SessionLimitReached when none may end."""
    if sid in sessions or len(sessions) < limit:
        return None
    oldest = min(sessions.values(), key=lambda s: s.last_call)
    if now - oldest.last_call < IDLE_S:
        raise SessionLimitReached(
            f"this planner serves {len(sessions)} sessions already, the most it keeps, each "
            f"called within the last {IDLE_S:g} s; end one (its plugin's cleanup) or serve "
            f"the others from another key or host"
        )
    return oldest
