/* The packages' headers: what one package may use of another. A body's inside is in
   src/body/bodyimpl.h, included only in src/body/. */
#pragma once

#include "util/util.h"
#include "element/element.h"
#include "material/material.h"
#include "shape/shape.h"
#include "mesh/mesh.h"
#include "contact/contact.h"
#include "body/body.h"
#include "compliance/compliance.h"
#include "collision/collision.h"
#include "scheme/scheme.h"
#include "io/io.h"
#include "scene/scene.h"
