#pragma once
/// \file isodel.h
/// All of isodel's public API in one include: `#include <isodel/isodel.h>`, link isodel::isodel.
///
///  - volume.h       read a sampled volume (.vdb, .mrc/.map/.ccp4, .inr, raw) into an
///                   openvdb::FloatGrid; Inside (which side of the isovalue is solid)
///  - mesh.h         mesh_isosurface: the surface M of Sigma = {F = v} (and tetrahedra), with
///                   the definition of F, Sigma and the tie rule; MeshOptions, MeshResult
///  - stats.h        MeshStats (what a run did and measured), ComponentTopology
///  - verify.h       verify_surface / verify_tets: independent certificates of a mesh
///  - surface_mesh.h SurfaceMesh, TetMesh and their file readers and writers
///  - adaptive.h     adaptive (octree) volumes: decimate, resample, files
///  - interrupt.h    progress, cancellation and trace lines (Interrupter)
///  - errors.h       the exceptions (InvalidInput, IoError, GuaranteeViolated, Cancelled)
///
/// Call openvdb::initialize() once before reading or meshing. A minimal program:
///
///     isodel::Volume vol = isodel::read_volume("in.mrc");
///     isodel::MeshOptions opt;
///     opt.isovalue = 0.5;
///     isodel::MeshResult r = isodel::mesh_isosurface(*vol.grid, opt);
///     isodel::write_surface_mesh("out.ply", r.surface);
#include <isodel/adaptive.h>
#include <isodel/errors.h>
#include <isodel/interrupt.h>
#include <isodel/mesh.h>
#include <isodel/stats.h>
#include <isodel/surface_mesh.h>
#include <isodel/verify.h>
#include <isodel/volume.h>
