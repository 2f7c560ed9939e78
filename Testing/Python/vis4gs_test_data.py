"""Where the Python tests find their inputs. The real third-party scenes live in
../shared/data beside the checkout (VIS4GS_SHARED_DATA_DIR); a test that needs them calls
shared_data_dir() first: without the folder it exits 77 (CTest's skip code for these tests)
naming it, and under CI=true, where the folder must be there, it fails."""
import os
import sys


def shared_data_dir():
    folder = os.environ.get("VIS4GS_SHARED_DATA_DIR", "")
    if folder and os.path.isdir(folder):
        return folder
    message = (f"the real third-party test data folder {folder or '(VIS4GS_SHARED_DATA_DIR unset)'}"
               " is absent (shared/data beside the checkout, or VIS4GS_SHARED_DATA_DIR)")
    if os.environ.get("CI") == "true":
        print(f"FAILED: {message}; under CI=true that is an error")
        sys.exit(1)
    print(f"{message}: skipped")
    sys.exit(77)
