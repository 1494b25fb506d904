"""Walking a Blender node tree as Cycles reads it: from the active Material Output down,
through reroutes and node groups, to the node and output socket that feed each input.

A place in the graph is a `Feed`: the node, its output socket, and the group nodes it sits in
(innermost last), so that a Group Input inside a group leads back out to what feeds the group
node's input, and a group node's output leads into the Group Output node inside it.
"""

from __future__ import annotations

from typing import NamedTuple

# Node groups nested deeper than this are refused (a group cannot contain itself in Blender,
# but a file can be edited to; the walk must end)
MAX_GROUP_DEPTH = 32


class Feed(NamedTuple):
    """node None: nothing is linked, the value is `socket`'s own (an input's default_value)."""

    node: object  # the bpy node whose output it is, or None
    socket: object  # that output socket, or the unlinked input socket
    groups: tuple  # the group nodes around `node`, outermost first


def output_node(tree):
    """The Material Output Cycles renders with: the active one of those for All or Cycles."""
    getter = getattr(tree, "get_output_node", None)
    if getter is not None:
        node = getter("CYCLES")
        if node is not None:
            return node
    outputs = [n for n in tree.nodes if n.type == "OUTPUT_MATERIAL"]
    active = [n for n in outputs if getattr(n, "is_active_output", False)]
    return (active or outputs or [None])[0]


def feed_of(socket, groups: tuple = ()) -> Feed:
    """What feeds input `socket` (of a node inside `groups`), past reroutes, into and out of
    groups: a node's output, or an unlinked input whose own value counts (a muted link is
    no link, as in Cycles)."""
    for _ in range(10000):  # reroute chains are finite; a malformed file must not hang us
        links = [link for link in socket.links if not getattr(link, "is_muted", False)]
        if not socket.is_linked or not links:
            return Feed(None, socket, groups)
        link = links[0]
        node, out = link.from_node, link.from_socket
        if node.type == "REROUTE":
            socket = node.inputs[0]
            continue
        if node.type == "GROUP" and node.node_tree is not None:
            inner = _group_output(node.node_tree)
            index = _socket_index(node.outputs, out)
            if len(groups) >= MAX_GROUP_DEPTH or inner is None or index >= len(inner.inputs):
                return Feed(node, out, groups)  # an empty or broken group: its caller says so
            socket, groups = inner.inputs[index], (*groups, node)
            continue
        if node.type == "GROUP_INPUT":
            index = _socket_index(node.outputs, out)
            if not groups or index >= len(groups[-1].inputs):
                return Feed(node, out, groups)  # a group's input used outside any group
            socket, groups = groups[-1].inputs[index], groups[:-1]
            continue
        return Feed(node, out, groups)
    return Feed(None, socket, groups)


def _group_output(tree):
    outputs = [n for n in tree.nodes if n.type == "GROUP_OUTPUT"]
    active = [n for n in outputs if getattr(n, "is_active_output", False)]
    return (active or outputs or [None])[0]


def _socket_index(sockets, socket) -> int:
    """The index of `socket` among the node's sockets of its kind, as group nodes and their
    Group Input/Output nodes number them alike (len(sockets) if it is not there)."""
    for index, candidate in enumerate(sockets):
        if candidate == socket:
            return index
    return len(sockets)


def node_label(node) -> str:
    """How a message names a node: its label or name, and its kind when that differs."""
    title = node.label or node.name
    kind = getattr(node, "bl_label", "") or node.type.title()
    return f"'{title}'" if title == kind else f"'{title}' ({kind})"
