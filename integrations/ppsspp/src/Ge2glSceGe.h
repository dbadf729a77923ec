// SPDX-License-Identifier: GPL-2.0-or-later
// Part of ge2gl's PPSSPP integration (integrations/ppsspp). This file is compiled into PPSSPP,
// which is licensed under the GNU GPL version 2.0 or later; so is this file.
//
// The sceGe_user HLE module served by ge2gl's GE. Register_sceGe_user() (Core/HLE/sceGe.cpp)
// calls this first: when PPSSPP's config selects ge2gl it registers this module's table under the
// same name and NIDs and returns true, and PPSSPP's own table is not registered.
#pragma once

bool Ge2gl_RegisterSceGeModule();
