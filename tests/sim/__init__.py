"""Tests of robotdesc.sim (a package so that test module names stay unique)."""
