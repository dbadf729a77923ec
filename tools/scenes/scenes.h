// SPDX-License-Identifier: MIT
// The scenes make_scenes writes as dumps/*.ppdmp, one file each (docs/scenes.md says what each one
// shows and exercises). Each draws a 480×272 frame into the 8888 frame buffer at VRAM 0x04000000.
#pragma once
#include "authoring/list_builder.h"

namespace ge::scenes {

void sceneLitTexturedSkinned(ListBuilder& b);
void sceneClutDxtSprites(ListBuilder& b);
void sceneBezierSpline(ListBuilder& b);
void sceneBlendStencilLogic(ListBuilder& b);
void sceneRenderToTexture(ListBuilder& b);

}  // namespace ge::scenes
