"""An ``xarray.DataTree`` put together from many datasets at once, as ``DataTree.from_dict``
makes it, at a fraction of the cost for trees of a thousand nodes.

xarray checks a node's alignment with the coordinates of its parents when it joins the tree:
about 0.5 ms a node, most of the time of opening a campaign. Runs of one layout share their index
objects (:mod:`mbds.data.references`), so the check of one run answers for the others: a node
whose coordinates that meet its parents' (the indexes named like theirs or along their
dimensions, and the sizes of the dimensions they share) are the very objects and sizes of a node
checked before is joined without checking again. Everything else is joined by xarray's own checks."""

from __future__ import annotations

import xarray as xr

try:  # joining without the check uses the tree's own fields; elsewhere every node is checked
    from xarray.core.datatree import _deduplicate_inherited_coordinates
except ImportError:  # pragma: no cover - another xarray
    _deduplicate_inherited_coordinates = None
_PROBE = xr.DataTree()
_FIELDS = _deduplicate_inherited_coordinates is not None and all(
    hasattr(_PROBE, name) for name in ("_set_node_data", "_set_parent", "_children", "_parent", "_name"))
del _PROBE


def grown(root: xr.Dataset, nodes: dict[str, xr.Dataset]) -> xr.DataTree:
    """The tree ``DataTree.from_dict({"/": root, **nodes})`` makes (paths absolute, parents made
    empty where missing), grown from the root down: each node is made once and joined to its
    parent once, where ``from_dict`` copies a node again for every level it is set through.
    The datasets of ``nodes`` become the nodes themselves: they must not be used elsewhere."""
    made = {"/": xr.DataTree(root)}
    children: dict[str, dict[str, xr.DataTree]] = {}
    for path in nodes:
        parts = path.strip("/").split("/")
        for depth in range(1, len(parts) + 1):
            here = "/" + "/".join(parts[:depth])
            if here not in made:
                made[here] = _node(nodes.get(here))
                children.setdefault("/" + "/".join(parts[:depth - 1]), {})[parts[depth - 1]] = made[here]
    checked: set[tuple] = set()
    for parent, named in children.items():  # parents first: a node joins before its children do
        _join(made[parent], named, checked)
    return made["/"]


def _node(ds: xr.Dataset | None) -> xr.DataTree:
    """A tree node holding ``ds`` itself: ``DataTree(ds)`` would copy it, at a third of the cost
    of opening a campaign."""
    if not _FIELDS:
        return xr.DataTree(ds)
    node = xr.DataTree()
    if ds is not None:
        node._set_node_data(ds)
    return node


def _join(parent: xr.DataTree, named: dict[str, xr.DataTree], checked: set[tuple]) -> None:
    """``parent.children = named`` for new nodes (without parents or children of their own): a
    node whose :func:`_meeting` key is in ``checked`` is joined as xarray joins a node once it has
    checked it, the others are checked by xarray as they join (and their keys kept in ``checked``)."""
    if not _FIELDS:
        parent.children = {**parent.children, **named}
        return
    indexes, sizes = dict(parent.xindexes), dict(parent.sizes)
    taken = set(parent.dataset.variables)
    here = (tuple(sorted((name, id(index)) for name, index in indexes.items())), tuple(sorted(sizes.items())))
    for name, child in named.items():
        key = (here, _meeting(child, indexes, sizes))
        if key in checked and name not in taken:
            parent._children[name] = child
            child._parent = parent
            child._name = name
            _deduplicate_inherited_coordinates(child, parent)
        else:
            child._set_parent(parent, name)  # what ``parent.children = ...`` does for each node
            checked.add(key)


def _meeting(node: xr.DataTree, indexes: dict, sizes: dict) -> tuple:
    """What xarray's alignment check of a parentless ``node`` with parents of ``indexes`` and
    ``sizes`` looks at: the node's indexes named like the parents' or along their dimensions (by
    identity), and the sizes of the dimensions they share."""
    variables = node.variables
    met = tuple(sorted((name, variables[name].dims, id(index)) for name, index in node.xindexes.items()
                       if name in indexes or any(d in sizes for d in variables[name].dims)))
    return met, tuple(sorted((d, n) for d, n in node.sizes.items() if d in sizes))
