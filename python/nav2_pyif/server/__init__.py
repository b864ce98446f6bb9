"""The planner host's inside: the `planner-host` command, the Zenoh queryables, the supervisor
and its workers, the session journal, the loader and the checks on what planners return.
Planner authors never import it; it imports the authors' API and the protocol, nothing of the
client, the runner, the tools or the reference planners."""
