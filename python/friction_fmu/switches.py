"""The items of a switch parameter (`law`, `solver`, `drive_source`, ...).

Switches are Integer variables (Int32 in the FMI 3.0 FMUs) with a declared type (co-simulation
engines ignore FMI 2.0 Enumerations, and ecos FMI 3.0 ones); each switch's description ends with
its numbered items:
"Friction law (1 coulomb, 2 dahl, 3 lugre)"."""
import re

_ITEMS = re.compile(r"\((\d+ \w+(?:, \d+ \w+)*)\)$")


def items(var):
    """{item name: integer} of a switch variable read by fmpy, or None for any other variable."""
    if var.type not in ("Integer", "Int32") or var.declaredType is None:
        return None
    listed = _ITEMS.search(var.description or "")
    if listed is None:
        return None
    return {name: int(number) for number, name in (entry.split(" ") for entry in listed.group(1).split(", "))}


def value(model_description, variable, item):
    """The integer of `item` of the switch named `variable`."""
    var = next(v for v in model_description.modelVariables if v.name == variable)
    return items(var)[item]
