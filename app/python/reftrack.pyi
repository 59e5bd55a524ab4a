# Type stubs of the Python module `reftrack` (app/python/ReftrackModule.cpp; keep the two in step).
import os
from typing import Any, Literal, Mapping, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

StrPath = Union[str, os.PathLike[str]]
Params = Union[None, StrPath, Mapping[str, Any]]

class Error(RuntimeError):
    """A failure of the engine (a bad map, file, parameter or frame), with its message."""

class Result:
    """What Tracker.track found in one frame."""

    @property
    def state(self) -> Literal["initialising", "tracking", "lost", "uncertain"]:
        """'uncertain': tracked, but predicted_error_px > pose.max_predicted_error_px."""
    @property
    def reason(self) -> str: ...
    @property
    def frame_index(self) -> int: ...
    @property
    def world_to_camera(self) -> Optional[npt.NDArray[np.float64]]:
        """4x4 world -> camera (X_camera = R X_world + t); None unless tracking."""
    @property
    def covariance(self) -> Optional[npt.NDArray[np.float64]]:
        """6x6 covariance of (t, r) of world_to_camera (metres, radians)."""
    @property
    def predicted_error_px(self) -> Optional[float]:
        """Overlay error (px) the covariance predicts for the overlay points; None without a pose."""
    @property
    def homography(self) -> Optional[npt.NDArray[np.float64]]:
        """3x3 reference pixel -> frame pixel (homography mode)."""
    @property
    def inliers(self) -> int: ...
    @property
    def reference_a(self) -> int: ...
    @property
    def reference_b(self) -> int: ...
    @property
    def relocalised(self) -> bool: ...
    @property
    def milliseconds(self) -> float: ...

class Tracker:
    """Tracks frames, in order, against a map (6-DOF) or a reference image (homography)."""

    @staticmethod
    def open_map(
        folder: StrPath,
        *,
        params: Params = None,
        motion_model: Optional[StrPath] = None,
        realtime: bool = False,
    ) -> Tracker: ...
    @staticmethod
    def open_reference(
        image: StrPath, *, camera: Optional[StrPath] = None, params: Params = None
    ) -> Tracker: ...
    def track(self, frame: npt.NDArray[np.uint8]) -> Result:
        """A uint8 image of the map's size, HxW grey or HxWx3 BGR."""
    def reset(self) -> None: ...
    def set_overlay_points(self, points: npt.ArrayLike) -> None:
        """Nx3 world points of the drawn object (6-DOF); 0x3 restores the default."""
    @property
    def mode(self) -> Literal["6dof", "homography"]: ...
    @property
    def image_size(self) -> Tuple[int, int]: ...
    @property
    def camera_matrix(self) -> Optional[npt.NDArray[np.float64]]: ...
