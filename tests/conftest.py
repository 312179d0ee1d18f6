import os
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))

# Tests derive afresh: the derivation cache (tested in test_derivation_cache.py) would let one test's
# derivation answer another's, and would write to the user's cache folder.
os.environ.setdefault("RIGIDKIN_NO_CACHE", "1")


def pytest_collection_modifyitems(config, items):
    """The modules that hold long cases (marked ``slow``) run first, each module kept together (its fixtures
    are made once): with ``-n 2`` a long case started last would leave the other worker idle at the end."""
    slow_modules = {item.module.__name__ for item in items if item.get_closest_marker("slow")}
    order = {id(item): i for i, item in enumerate(items)}
    items.sort(key=lambda item: (item.module.__name__ not in slow_modules, order[id(item)]))
