import os
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))

# Tests derive afresh: the derivation cache (tested in test_derivation_cache.py) would let one test's
# derivation answer another's, and would write to the user's cache folder.
os.environ.setdefault("RIGIDKIN_NO_CACHE", "1")
