"""Perception: the OpenCV pipeline on drawn frames, then camera vs truth on rendered frames."""

from __future__ import annotations

import cv2
import numpy as np
import pytest

from behaviours.perception import (
    above_relations,
    describe_blob,
    largest_blob,
    observe_image,
)

W, H = 320, 240
RED, BLUE, GREEN, DARK, GREY = (220, 30, 30), (30, 30, 220), (30, 200, 30), (5, 5, 5), (190,) * 3


def _frame() -> np.ndarray:
    return np.full((H, W, 3), GREY, np.uint8)


def _rotated(image: np.ndarray, centre, size, angle: float, colour) -> None:
    box = cv2.boxPoints((centre, size, angle)).astype(np.int32)
    cv2.fillPoly(image, [box], colour)


def test_descriptors_of_an_upright_rectangle_are_table_5_1():
    image = _frame()
    cv2.rectangle(image, (100, 150), (149, 169), RED, -1)  # 50 x 20 px
    obs = observe_image(image, {"body": 0.05})
    body = obs.parts["body"]
    assert body.area == pytest.approx(1000 / (W * H))
    assert body.rectangleness == pytest.approx(0.4)
    assert body.squareness == pytest.approx(1.0)
    assert body.centre == pytest.approx((124.5, 159.5))
    assert body.bbox == (100, 150, 50, 20)
    assert set(obs.parts) == {"body"}


def test_rotated_rectangle_keeps_its_shape_through_the_min_area_rectangle():
    image = _frame()
    _rotated(image, (160, 100), (80, 20), 30.0, BLUE)
    lid = observe_image(image, {"body": 0.05}).parts["lid"]
    assert lid.rectangleness == pytest.approx(0.25, abs=0.03)
    assert lid.squareness > 0.9
    # the axis-aligned box of a tilted bar is much squarer than the bar itself
    x, y, w, h = lid.bbox
    assert min(w, h) / max(w, h) > 0.4


def test_l_shaped_blob_is_less_square_than_a_rectangle():
    blob = np.zeros((H, W), np.uint8)
    cv2.rectangle(blob, (50, 50), (149, 59), 255, -1)
    cv2.rectangle(blob, (50, 50), (59, 149), 255, -1)
    part = describe_blob("handle", blob)
    assert part.squareness < 0.25
    assert part.rectangleness == pytest.approx(1.0, abs=0.02)


def test_largest_blob_ignores_specks_and_smaller_components():
    mask = np.zeros((H, W), np.uint8)
    mask[10:12, 10:12] = 255
    assert largest_blob(mask) is None
    mask[100:120, 100:140] = 255
    mask[200:205, 200:205] = 255
    blob = largest_blob(mask)
    assert blob is not None and int(np.count_nonzero(blob)) == 800


def test_opening_is_dark_height_scaled_by_the_marker():
    image = _frame()
    cv2.rectangle(image, (100, 150), (149, 169), RED, -1)  # 50 px long -> 1 mm per pixel
    cv2.rectangle(image, (90, 100), (159, 139), DARK, -1)  # 40 px high dark region
    obs = observe_image(image, {"body": 0.05})
    assert obs.opening == pytest.approx(0.040, abs=1e-9)
    image2 = _frame()
    cv2.rectangle(image2, (100, 150), (124, 159), RED, -1)  # 25 px long -> 2 mm per pixel
    cv2.rectangle(image2, (90, 100), (159, 139), DARK, -1)
    assert observe_image(image2, {"body": 0.05}).opening == pytest.approx(0.080, abs=1e-9)


def test_no_dark_region_or_no_marker_means_no_opening():
    image = _frame()
    cv2.rectangle(image, (100, 150), (149, 169), RED, -1)
    assert observe_image(image, {"body": 0.05}).opening == 0.0
    lone_dark = _frame()
    cv2.rectangle(lone_dark, (90, 100), (159, 139), DARK, -1)
    assert observe_image(lone_dark, {"body": 0.05}).opening == 0.0


def test_all_three_colours_are_told_apart_and_grey_white_yellow_are_ignored():
    image = _frame()
    cv2.rectangle(image, (0, 0), (319, 30), (255, 255, 255), -1)
    cv2.rectangle(image, (0, 200), (319, 239), (230, 210, 40), -1)  # yellow
    cv2.rectangle(image, (100, 150), (149, 169), RED, -1)
    cv2.rectangle(image, (100, 90), (149, 109), BLUE, -1)
    cv2.rectangle(image, (200, 60), (299, 69), GREEN, -1)
    obs = observe_image(image, {"body": 0.05})
    assert set(obs.parts) == {"body", "lid", "handle"}
    assert obs.parts["handle"].rectangleness == pytest.approx(0.1)
    assert set(obs.above) == {("lid", "body"), ("handle", "body"), ("handle", "lid")}


def test_above_needs_a_margin():
    image = _frame()
    cv2.rectangle(image, (10, 100), (59, 119), RED, -1)
    cv2.rectangle(image, (100, 101), (149, 120), BLUE, -1)  # one pixel lower: not "above"
    obs = observe_image(image, {"body": 0.05})
    assert above_relations(obs.parts) == ()
