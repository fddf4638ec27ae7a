"""The exporter's notes: what a .blend holds that phongcl's scene cannot say, printed one line each
("export_scene: ...", which scripts/checks/61-blender-notes.sh reads), never dropped silently."""


def note(text):
    print("export_scene: " + text)


def rounded(values, digits=7):
    return [round(float(v), digits) for v in values]


def unlinked_value(owner, node, socket_name, what):
    """A socket's own value, with a note naming the node that feeds it where one does (phongcl reads values,
    not node graphs)."""
    socket = node.inputs[socket_name]
    if socket.is_linked:
        source = socket.links[0].from_node
        note("%s: %s's %s is fed by '%s' (%s), which phongcl cannot evaluate: exported the socket's own value %s"
             % (owner, node.name, socket_name, source.name, source.bl_idname,
                rounded(socket.default_value[:3] if what == "colour" else [socket.default_value], 4)))
    return socket.default_value
