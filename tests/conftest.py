"""Test-session settings shared by every test module."""

import os
import tempfile

# compiled mechanisms go to a cache private to this test session, never the user's
os.environ.setdefault("LINKAGE_SYM_CACHE", tempfile.mkdtemp(prefix="linkage_sym_cache_"))
