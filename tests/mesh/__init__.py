"""Tests of robotdesc.mesh (a package so that test module names stay unique)."""
