"""Test-session settings shared by every test module."""

import os
import tempfile

# compiled mechanisms go to a cache private to this test session, never the user's
os.environ.setdefault("LINKAGE_SYM_CACHE", tempfile.mkdtemp(prefix="linkage_sym_cache_"))

# Property tests draw the same examples in every run (each test's seed from its name), so a
# result does not depend on the run: a search for new counterexamples is asked for
# (HYPOTHESIS_PROFILE=explore), and what it finds becomes an @example of the test.
from hypothesis import settings  # noqa: E402

settings.register_profile("repeatable", derandomize=True)
settings.register_profile("explore", derandomize=False)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "repeatable"))
