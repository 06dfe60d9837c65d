def check_manifest(directory=HERE):
    """The unit's manifest beside the wrapper states the same ports and widths, or an error
    names the port and both widths."""
    path = Path(directory) / (UNIT["top"] + ".json")
    if not path.is_file():
        return
    ports = {p["name"]: (p["direction"], p["width"]) for p in json.loads(path.read_text())["ports"]}
    mine = {p["name"]: (p["direction"], p["width"]) for p in UNIT["ports"]}
    for name in sorted(set(ports) | set(mine)):
        if ports.get(name) != mine.get(name):
            raise ValueError(
                f"{UNIT['top']}: port {name} is {mine.get(name)} in this wrapper but {ports.get(name)} "
                f"in {path.name} (direction, width): regenerate the unit and its wrapper together"
            )

